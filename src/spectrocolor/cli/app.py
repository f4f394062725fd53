"""``spectrocolor app``: serve the SPECTRA explorer on this machine and open it in a browser.

The server listens on the loopback address (127.0.0.1) and answers only requests addressed to
it by a loopback name (127.0.0.1, localhost, [::1]) and its port. Any other ``--host`` opens it
to the network; that needs ``--allow-remote`` and prints a warning, since the explorer has no
accounts and no encryption.
"""

from __future__ import annotations

import ipaddress
import os
import socket
import sys

from . import UserError


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "app",
        help="start the SPECTRA explorer (a local web app) and open it in the browser",
        description="Serve the explorer of Sällström's five SPECTRA settings on a local port.",
    )
    p.add_argument("--port", type=int, default=8765,
                   help="TCP port (default 8765; 0 picks a free one)")
    p.add_argument("--host", default="127.0.0.1",
                   help="address to bind (default 127.0.0.1: only this machine can connect); "
                   "a non-loopback address needs --allow-remote")
    p.add_argument("--allow-remote", action="store_true",
                   help="allow a --host that other machines can reach (no accounts, no TLS: "
                   "anyone who can reach the port can use the explorer)")
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


def _bind(host: str, port: int) -> socket.socket:
    if not 0 <= port <= 65535:
        raise UserError(f"--port must be 0-65535, got {port}")
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    # accepted connections inherit it: without, a response written in two parts waits for the
    # client's delayed ACK, 40 ms per request on a kept-alive connection
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    try:
        sock.bind((host, port))
    except OSError as exc:
        sock.close()
        raise UserError(f"cannot listen on {host}:{port} ({exc.strerror}); try --port 0") from None
    return sock


def run(args) -> int:
    try:
        import uvicorn

        from ..app.server import create_app
    except ImportError as exc:
        raise UserError(
            f"the explorer needs the 'app' extra ({exc.name} is missing): "
            "pip install 'spectrocolor[app]'") from None
    remote = not is_loopback(args.host)
    if remote and not args.allow_remote:
        raise UserError(f"--host {args.host!r} is not a loopback address: other machines could "
                        "use the explorer; add --allow-remote if that is what you want")
    if remote:
        print(f"warning: serving on {args.host}: anyone who can reach this port can use the "
              "explorer (no accounts, no encryption)", file=sys.stderr, flush=True)
    sock = _bind(args.host.strip("[]"), args.port)
    host, port = sock.getsockname()[:2]
    shown = f"[{host}]" if ":" in host else host
    url = f"http://{shown}:{port}/"
    print(f"spectrocolor explorer: {url}  (Ctrl+C stops it)", flush=True)
    if not args.no_browser and _has_display():
        import webbrowser

        webbrowser.open(url)
    app = create_app(port=port, check_host=not remote)
    from ..app.http_protocol import JSONErrorH11Protocol  # malformed HTTP gets the JSON error shape too

    config = uvicorn.Config(app, log_level="warning", http=JSONErrorH11Protocol)
    server = uvicorn.Server(config)
    try:
        server.run(sockets=[sock])
    except KeyboardInterrupt:
        pass
    return 0
