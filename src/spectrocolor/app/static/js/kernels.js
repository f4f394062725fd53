// After a fresh start the server compiles its kernels in the background; until they are ready its
// results come from the slower NumPy path (the same numbers, to rounding), and each answer says so
// in the X-Spectrocolor-Kernels header (spectrocolor.app.kernels). This shows a small note then,
// and hides it once an answer comes without the header (the kernels are ready).

const NOTE_ID = "kernel-status";
export const NUMPY_PATH_TEXT = "compiled kernels warming up — this result used the slower NumPy path";

/** Show or hide the note after an answer of the server, from its X-Spectrocolor-Kernels header. */
export function showKernelStatus(response) {
  const status = response.headers.get("X-Spectrocolor-Kernels");
  let note = document.getElementById(NOTE_ID);
  if (status === "numpy-path") {
    if (!note) {
      note = document.createElement("p");
      note.id = NOTE_ID;
      note.className = "kernel-status";
      note.setAttribute("role", "status");
      document.body.append(note);
    }
    note.textContent = NUMPY_PATH_TEXT;
    note.hidden = false;
  } else if (status === null && note) {
    note.hidden = true;
  }
}
