// The server's JSON API: every colour number the page shows comes from the library through it.

import {clientHeaders} from "./client.js";
import {showKernelStatus} from "./kernels.js";
import {busyFetch} from "./busy.js";

export class ApiError extends Error {}

export async function api(path, body) {
  const opts = body === undefined ? {headers: clientHeaders()} : {method: "POST",
    headers: {"Content-Type": "application/json", ...clientHeaders()}, body: JSON.stringify(body)};
  let res;
  try {
    res = await busyFetch(path, opts);  // the "computing…" note; a busy server's 429 tried again
  } catch (err) {
    throw new ApiError(`the explorer's server did not answer (${err.message}); is it still running?`);
  }
  if (!res.ok) {
    let msg = `${res.status} ${res.statusText}`;
    try { msg = (await res.json()).error || msg; } catch { /* not JSON */ }
    throw new ApiError(msg);
  }
  showKernelStatus(res);
  return res;
}

export const apiJSON = async (path, body) => (await api(path, body)).json();
