// Talking to the bridge: JSON over HTTP (/geometry, /frame) and the /ws
// WebSocket, which reconnects by itself every second after it closes.

const RECONNECT_MS = 1000;

/**
 * GETs `path` and returns its JSON. Throws an Error whose message is the
 * bridge's {"error": ...} text when there is one; error.status is the HTTP
 * status (0 when the bridge could not be reached).
 */
export async function fetchJson(path) {
  let response;
  try {
    response = await fetch(path, { cache: 'no-store' });
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
      ws = new WebSocket(`${scheme}://${location.host}/ws`);
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
