// Talking to the bridge: JSON over HTTP (/geometry, /frame) and the /ws
// WebSocket, which reconnects by itself every second after it closes.
// Each carries the bridge's secret (docs/security.md), which the page
// reads from the ?token= of its address.

const RECONNECT_MS = 1000;
const TOKEN_KEY = 'hapticctl-view-token';

/**
 * The bridge's secret. It comes in the page's address; the page keeps it
 * in this tab's sessionStorage (a reload finds it there) and takes it out
 * of the address bar, so that it is not shown, bookmarked or shared.
 */
const TOKEN = takeToken();

function takeToken() {
  const url = new URL(location.href);
  const given = url.searchParams.get('token');
  if (!given) {
    try {
      return sessionStorage.getItem(TOKEN_KEY) ?? '';
    } catch {
      return ''; // storage disabled: the address must carry it
    }
  }
  try {
    sessionStorage.setItem(TOKEN_KEY, given);
  } catch {
    // Kept in memory only: a reload needs the address again.
  }
  url.searchParams.delete('token');
  history.replaceState(history.state, '', url);
  return given;
}

/** `path` with the secret in its query. */
function withToken(path) {
  return `${path}?token=${encodeURIComponent(TOKEN)}`;
}

/**
 * GETs `path` and returns its JSON. Throws an Error whose message is the
 * bridge's {"error": ...} text when there is one; error.status is the HTTP
 * status (0 when the bridge could not be reached).
 */
export async function fetchJson(path) {
  let response;
  try {
    response = await fetch(withToken(path), { cache: 'no-store' });
  } catch (e) {
    throw httpError(`${path}: ${e.message}`, 0);
  }
  let body = null;
  try {
    body = await response.json();
  } catch {
    // Not JSON: reported below.
  }
  if (!response.ok) {
    throw httpError(body?.error ?? `${path}: HTTP ${response.status}`, response.status);
  }
  if (body === null) throw httpError(`${path}: the answer is not JSON`, response.status);
  return body;
}

function httpError(message, status) {
  const error = new Error(message);
  error.status = status;
  return error;
}

/**
 * The WebSocket to ws://<page host>/ws. Calls onOpen() when (re)connected,
 * onClose() when the connection goes away (then retries every second), and
 * onMessage(object) for every JSON text frame.
 */
export class BridgeSocket {
  constructor({ onOpen, onClose, onMessage }) {
    this.handlers = { onOpen, onClose, onMessage };
    this.ws = null;
  }

  connect() {
    const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
    let ws;
    try {
      ws = new WebSocket(`${scheme}://${location.host}${withToken('/ws')}`);
    } catch {
      this.retry();
      return;
    }
    this.ws = ws;
    ws.onopen = () => this.handlers.onOpen();
    ws.onmessage = (event) => this.receive(event.data);
    ws.onclose = () => {
      this.ws = null;
      this.handlers.onClose();
      this.retry();
    };
    // An error is always followed by a close, which does the work.
    ws.onerror = () => {};
  }

  get isOpen() {
    return this.ws?.readyState === WebSocket.OPEN;
  }

  /** Sends `message` as JSON; returns false if the socket is not open. */
  send(message) {
    if (!this.isOpen) return false;
    this.ws.send(JSON.stringify(message));
    return true;
  }

  receive(data) {
    if (typeof data !== 'string') return;
    let message;
    try {
      message = JSON.parse(data);
    } catch {
      return; // Not JSON: ignored.
    }
    if (message && typeof message.type === 'string') this.handlers.onMessage(message);
  }

  retry() {
    setTimeout(() => this.connect(), RECONNECT_MS);
  }
}
