// This tab's client token: random, kept for the tab's life (sessionStorage), sent with every API
// request so that the server's per-client limits tell this tab from others on the same machine.

const KEY = "spectrocolor-client";

function token() {
  try {
    let value = sessionStorage.getItem(KEY);
    if (!value) {
      value = Array.from(crypto.getRandomValues(new Uint8Array(16)), (b) => b.toString(16).padStart(2, "0")).join("");
      sessionStorage.setItem(KEY, value);
    }
    return value;
  } catch {
    return null; // storage refused: the server treats the tab as its address's shared client
  }
}

/** The headers every API request carries (the token, when there is one). */
export function clientHeaders() {
  const value = token();
  return value ? {"X-Spectrocolor-Client": value} : {};
}
