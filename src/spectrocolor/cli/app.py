"""``spectrocolor app``: serve the SPECTRA explorer on this machine and open it in a browser.

The server listens on the loopback address (127.0.0.1) and answers only requests addressed to
it by a loopback name (127.0.0.1, localhost, [::1]) and its port. Any other ``--host`` opens it
to the network; that needs ``--allow-remote`` and prints a warning, since the explorer has no
accounts and no encryption.

It prints one line per step: the URL it serves at, then that the compiled kernels are being
compiled in the background (:mod:`spectrocolor.app.kernels`; results use the NumPy path
meanwhile, and say so), then when they are ready. ``make run`` starts it with
``SPECTROCOLOR_MAKE_RUN=1``, so that its advice names make's variables (``make run PORT=8766``)
rather than options that make cannot pass on.
"""

from __future__ import annotations

import errno
import ipaddress
import os
import signal
import socket
import sys

from . import UserError, install_command

#: Set (to 1) by ``make run``: advice then names make's variables instead of the options.
MAKE_RUN_VARIABLE = "SPECTROCOLOR_MAKE_RUN"
#: Ports after a busy one that are tried for a free one to suggest.
PORTS_TRIED = 20


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "app",
        help="start the SPECTRA explorer (a local web app) and open it in the browser",
        description="Serve the explorer of Sällström's five SPECTRA settings on a local port.",
    )
    p.add_argument("--port", type=int, default=8765,
                   help="TCP port (default 8765; 0 picks a free one)")
    p.add_argument("--host", default=None,
                   help="address to bind (default 127.0.0.1: only this machine can connect; "
                   "with --classroom, this machine's local-network address); "
                   "a non-loopback address needs --allow-remote (or --classroom)")
    p.add_argument("--allow-remote", action="store_true",
                   help="allow a --host that other machines can reach (no accounts, no TLS: "
                   "anyone who can reach the port can use the explorer)")
    p.add_argument("--classroom", action="store_true",
                   help="open a class: serve the local network, students join with a random "
                   "code (address and QR code printed); see docs/classroom.md")
    p.add_argument("--no-browser", action="store_true", help="print the URL, open nothing")
    p.set_defaults(handler=run)


def _has_display() -> bool:
    if sys.platform in ("darwin", "win32"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def is_loopback(host: str) -> bool:
    """Whether ``host`` (a name or an address, IPv6 with or without brackets) is loopback only.

    Examples
    --------
    >>> [is_loopback(h) for h in ("127.0.0.1", "localhost", "::1", "[::1]", "0.0.0.0", "")]
    [True, True, True, True, False, False]
    """
    if host.lower() == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def started_by_make() -> bool:
    """Whether ``make run`` started this command (``SPECTROCOLOR_MAKE_RUN=1``)."""
    return os.environ.get(MAKE_RUN_VARIABLE, "") == "1"


def port_advice(port: int | None, by_make: bool) -> str:
    """How to choose another port, as a command to run: with make's ``PORT=`` or with ``--port``.

    Parameters
    ----------
    port : int or None
        A port to suggest; None suggests only 0 (any free port).
    by_make : bool
        Whether the user started the explorer with ``make run``.

    Examples
    --------
    >>> port_advice(8766, by_make=True)
    'run `make run PORT=8766` (or PORT=0 for any free port)'
    >>> port_advice(None, by_make=False)
    'run `spectrocolor app --port 0` (any free port)'
    """
    if by_make:
        return (f"run `make run PORT={port}` (or PORT=0 for any free port)" if port is not None
                else "run `make run PORT=0` (any free port)")
    return (f"run `spectrocolor app --port {port}` (or --port 0 for any free port)"
            if port is not None else "run `spectrocolor app --port 0` (any free port)")


def _socket(host: str) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    return sock


def _free_port_after(host: str, port: int) -> int | None:
    """The first of the :data:`PORTS_TRIED` ports after ``port`` that ``host`` can bind now."""
    for candidate in range(port + 1, min(port + 1 + PORTS_TRIED, 65536)):
        with _socket(host) as probe:
            try:
                probe.bind((host, candidate))
            except OSError:
                continue
            return candidate
    return None


def _bind(host: str, port: int) -> socket.socket:
    by_make = started_by_make()
    if not 0 <= port <= 65535:
        raise UserError(f"{'PORT' if by_make else '--port'} must be 0-65535 (0: any free port), "
                        f"got {port}")
    sock = _socket(host)
    # accepted connections inherit it: without, a response written in two parts waits for the
    # client's delayed ACK, 40 ms per request on a kept-alive connection
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    try:
        sock.bind((host, port))
    except OSError as exc:
        sock.close()
        if exc.errno == errno.EADDRINUSE:
            raise UserError(f"port {port} is busy (another program, perhaps an explorer already "
                            f"started, listens on {host}:{port}); "
                            f"{port_advice(_free_port_after(host, port), by_make)}") from None
        if exc.errno == errno.EACCES and 0 < port < 1024:
            raise UserError(f"port {port} needs administrator rights ({exc.strerror}); choose one "
                            f"above 1023: {port_advice(8765, by_make)}") from None
        raise UserError(f"cannot listen on {host}:{port} ({exc.strerror}); "
                        f"{port_advice(None, by_make)}") from None
    return sock


def run(args) -> int:
    try:
        import uvicorn

        from ..app.server import create_app
    except ImportError as exc:
        if (exc.name or "spectrocolor").split(".")[0] == "spectrocolor":
            raise  # a module of this package: a bug, not a missing extra
        raise UserError(f"the explorer needs the extra 'app' ({exc.name} is missing); install it "
                        f"with: {install_command('app', exc.name)}") from None
    if getattr(args, "classroom", False):  # classroom mode (issue 30)
        return _run_classroom(args)
    args.host = args.host or "127.0.0.1"
    remote = not is_loopback(args.host)
    if remote and not args.allow_remote:
        allow = "ALLOW_REMOTE=1 to `make run`" if started_by_make() else "--allow-remote"
        raise UserError(f"--host {args.host!r} is not a loopback address: other machines could "
                        f"use the explorer; add {allow} if that is what you want")
    if remote:
        print(f"warning: serving on {args.host}: anyone who can reach this port can use the "
              "explorer (no accounts, no encryption)", file=sys.stderr, flush=True)
    from ..app.http_protocol import ACCEPT_BACKLOG, JSONErrorH11Protocol

    sock = _bind(args.host.strip("[]"), args.port)
    # listen before the address is announced: a browser opened at once (ours, or the user's
    # click) then waits in the backlog until the server accepts, instead of being refused
    sock.listen(ACCEPT_BACKLOG)
    host, port = sock.getsockname()[:2]
    shown = f"[{host}]" if ":" in host else host
    url = f"http://{shown}:{port}/"
    say(f"serving at {url}  (Ctrl+C stops it)")
    if not args.no_browser and _has_display():
        import webbrowser

        webbrowser.open(url)
    from ..app.kernels import BackgroundCompilation

    compilation = BackgroundCompilation.start(report=say)  # before any worker process starts
    # uvicorn stops on SIGTERM, then raises it again: end through the finally below instead
    signal.signal(signal.SIGTERM, _exit_on_signal)
    try:
        app = create_app(port=port, check_host=not remote)
        # malformed HTTP: the JSON error shape too; bounded connections (see http_protocol)
        config = uvicorn.Config(app, log_level="warning", http=JSONErrorH11Protocol,
                                backlog=ACCEPT_BACKLOG)
        server = uvicorn.Server(config)
        try:
            server.run(sockets=[sock])
        except KeyboardInterrupt:
            pass
    finally:
        if compilation is not None:
            compilation.stop()
    return 0


def _run_classroom(args) -> int:
    """``spectrocolor app --classroom``: the class's join address, QR code and teacher address."""
    import uvicorn

    from ..app.classroom import Classroom, lan_address, qr_terminal
    from ..app.http_protocol import ACCEPT_BACKLOG, JSONErrorH11Protocol
    from ..app.server import create_app

    host = args.host or lan_address()
    if host is None:
        raise UserError("could not find this machine's local-network address (is it on a "
                        "network?); give it with " + ("HOST=ADDR" if started_by_make()
                                                      else "--host ADDR"))
    sock = _bind(host.strip("[]"), args.port)
    sock.listen(ACCEPT_BACKLOG)
    bound, port = sock.getsockname()[:2]
    classroom = Classroom(bound, port)
    say(f"class open at {classroom.origin}/  (Ctrl+C ends the class)")
    say(f"students join at {classroom.join_url()}")
    print(qr_terminal(classroom.join_url()), end="", flush=True)
    say(f"teacher's page (keep this address to yourself): {classroom.teacher_url()}")
    if not args.no_browser and _has_display():
        import webbrowser

        webbrowser.open(classroom.teacher_url())
    from ..app.kernels import BackgroundCompilation

    compilation = BackgroundCompilation.start(report=say)
    signal.signal(signal.SIGTERM, _exit_on_signal)
    try:
        app = create_app(classroom=classroom)
        config = uvicorn.Config(app, log_level="warning", http=JSONErrorH11Protocol,
                                backlog=ACCEPT_BACKLOG, timeout_graceful_shutdown=5)

        class ClassServer(uvicorn.Server):
            async def shutdown(self, sockets=None):
                classroom.close()  # the event streams end first, so the server can stop
                await super().shutdown(sockets)

        try:
            ClassServer(config).run(sockets=[sock])
        except KeyboardInterrupt:
            pass
    finally:
        if compilation is not None:
            compilation.stop()
    return 0


def _exit_on_signal(signum, _frame):
    raise SystemExit(128 + signum)


def say(line: str) -> None:
    """Print one line of the explorer's progress (``spectrocolor explorer: …``), at once."""
    print(f"spectrocolor explorer: {line}", flush=True)
