// Entry point of the haptic scene viewer. Wires the modules together:
//   connection.js   HTTP (/geometry, /frame) and the /ws WebSocket
//   geometry.js     meshes from /geometry
//   frame_view.js   one frame in 3D: tool poses, contact features, arrows
//   controls.js     driving a tool (take / release, mouse, keys, pose stream)
//   stage.js        renderer, camera, lights, grid
//   panel.js        banner, status line, legend, tables
//   strip_chart.js  force against time
// and keeps window.viewerState (read by browser tests) up to date.
//
// index.html            live: WebSocket frames, drawn with requestAnimationFrame
// index.html?snapshot=1 one /geometry + one /frame, drawn once, then
//                       document.body.dataset.ready = "1" and title "ready"

import * as THREE from 'three';
import { BridgeSocket, fetchJson } from './connection.js';
import { DriveControls } from './controls.js';
import { contactsOf, FrameView } from './frame_view.js';
import { SceneObjects } from './geometry.js';
import { Panel } from './panel.js';
import { isFiniteArray } from './pose.js';
import { Stage } from './stage.js';
import { StripChart } from './strip_chart.js';

const SNAPSHOT = new URLSearchParams(location.search).get('snapshot') === '1';
const GEOMETRY_RETRY_MS = 1000;  // also the shortest time between two /geometry fetches
const PANEL_INTERVAL_MS = 100;   // tables are refreshed at most 10 times a second

/** What the page shows, for browser tests (names fixed by the test contract). */
const state = {
  connected: false,       // WebSocket open and the bridge reaches the server
  scene: '',
  revision: -1,           // of the geometry drawn; -1 before the first /geometry
  objects: [],
  frames: 0,              // frames received
  lastStep: -1,
  heldTool: null,         // the tool this page drives
  driveState: 'none',     // last drive answer: held | released | refused (or taking / releasing)
  tools: {},              // name -> {device_p, proxy_p, force_n, force_magnitude_n, holder, force_clamped}
  contacts: [],
  bodies: {},             // free body name -> {mesh_p (where drawn), held, touching_tools}
  highlighted: {
    tool_vertices: 0, tool_edges: 0, tool_faces: 0,
    object_vertices: 0, object_edges: 0, object_faces: 0,
  },
  arrows: { reversing_vector: false, force: false },
  status: '',             // banner and status line text
  posesSent: 0,
  // camera: {target: [x, y, z], distance} (metres), read live from the stage
};
window.viewerState = state;

const panel = new Panel({
  onTake: () => drive.take(panel.selectedTool()),
  onRelease: () => drive.release(),
});

let stage;
try {
  stage = new Stage(document.getElementById('view'), SNAPSHOT);
} catch (e) {
  panel.setBanner('webgl', `This browser cannot draw 3D (WebGL): ${e.message}`);
  state.status = panel.statusText();
  throw e;
}
Object.defineProperty(state, 'camera', { enumerable: true, get: () => stage.view() });
const objects = new SceneObjects(stage.scene);
const frameView = new FrameView(stage.scene);
const chart = new StripChart(document.getElementById('strip-chart'));

let socket = null;          // live mode only
let serverConnected = true; // from "status" messages: does the bridge reach the server?
let serverMessage = '';
let helloTools = [];
let latestFrame = null;     // the newest "frame" message
let frameDirty = false;     // latestFrame or the meshes changed since last drawn
let panelDirty = true;
let lastPanelUpdate = -Infinity;
let geometryLoading = false;
let lastGeometryAttempt = -Infinity;
let geometryRetryTimer = null;
// The camera is framed on the scene when the geometry first arrives, and once
// more when the first frame has placed the tools.
let cameraFramed = false;
let cameraFramedWithFrame = false;

const drive = new DriveControls({
  canvas: stage.canvas,
  camera: stage.camera,
  orbit: stage.orbit,
  send: (message) => socket?.send(message) ?? false,
  devicePose,
  selectedTool: () => panel.selectedTool(),
  state,
  onChange: () => {
    panel.showDrive(state.heldTool, state.driveState, drive.message);
    refreshStatus();
  },
});

window.viewerTest = {
  take: (tool) => drive.take(tool),
  release: () => drive.release(),
  moveBy: (offset) => drive.moveBy(offset),
};

// F: the camera frames the driven tool (else the chosen one) and its
// contacts, which are millimetres across where the whole table is not.
window.addEventListener('keydown', (e) => {
  if (e.ctrlKey || e.metaKey || e.altKey || e.key.toLowerCase() !== 'f') return;
  if (frameOnTool()) e.preventDefault();
});

// ---- geometry ----------------------------------------------------------------

/** Fetches /geometry and rebuilds the meshes; true on success. Retries on failure (live mode). */
async function loadGeometry() {
  if (geometryLoading) return false;
  geometryLoading = true;
  lastGeometryAttempt = performance.now();
  clearTimeout(geometryRetryTimer);
  try {
    showGeometry(await fetchJson('/geometry'));
    panel.setBanner('geometry', null);
    return true;
  } catch (e) {
    panel.setBanner('geometry', `Cannot load the scene geometry: ${e.message}`);
    if (!SNAPSHOT) geometryRetryTimer = setTimeout(loadGeometry, GEOMETRY_RETRY_MS);
    return false;
  } finally {
    geometryLoading = false;
    refreshStatus();
  }
}

function showGeometry(geometry) {
  objects.rebuild(geometry);
  state.scene = String(geometry.scene ?? state.scene);
  state.revision = Number.isFinite(geometry.revision) ? geometry.revision : -1;
  state.objects = objects.names();
  refreshToolNames();
  if (!cameraFramed) {
    stage.frameOn(objects.boundingBox());
    cameraFramed = true;
  }
  frameDirty = true;
}

/** Refetches /geometry when a frame carries another revision (at most once a second). */
function checkRevision(frame) {
  if (!Number.isFinite(frame.revision) || frame.revision === state.revision) return;
  if (performance.now() - lastGeometryAttempt >= GEOMETRY_RETRY_MS) loadGeometry();
}

// ---- messages from the bridge ------------------------------------------------

function handleMessage(message) {
  switch (message.type) {
    case 'hello':
      // The scene and its tools only: whether the bridge reaches the server
      // is the status message's to say (a page opening while the server is
      // away gets a hello, then the status that says so).
      state.scene = String(message.scene ?? '');
      helloTools = Array.isArray(message.tools) ? message.tools.map(String) : [];
      refreshToolNames();
      break;
    case 'frame':
      receiveFrame(message);
      break;
    case 'status':
      setServerConnected(Boolean(message.connected), String(message.message ?? ''));
      break;
    case 'drive':
      drive.handleDrive(message);
      break;
    default:
      break; // unknown types are ignored
  }
}

function receiveFrame(frame) {
  state.frames++;
  if (Number.isFinite(frame.step)) state.lastStep = frame.step;
  latestFrame = frame;
  frameDirty = true;
  panelDirty = true;
  recordFrameState(frame);
  chart.add(frame);
  if (!SNAPSHOT) {
    if (!serverConnected) setServerConnected(true, ''); // frames flow again
    checkRevision(frame);
    refreshToolNames();
  }
  refreshStatus();
}

/** Copies a frame's tools and contacts into viewerState. */
function recordFrameState(frame) {
  const tools = Array.isArray(frame.tools) ? frame.tools : [];
  state.tools = {};
  state.contacts = [];
  for (const tool of tools) {
    const force = isFiniteArray(tool.force_n, 3) ? tool.force_n : [0, 0, 0];
    state.tools[tool.name] = {
      device_p: tool.device?.p ?? null,
      proxy_p: tool.proxy?.p ?? null,
      force_n: force,
      force_magnitude_n: Math.hypot(force[0], force[1], force[2]),
      holder: String(tool.holder ?? ''),
      force_clamped: Boolean(tool.force_clamped),
    };
    for (const contact of contactsOf(tool)) {
      state.contacts.push({
        tool: tool.name,
        object: contact.object,
        kind: contact.kind,
        depth_m: contact.depth_m,
        reversing_vector_m: contact.reversing_vector_m ?? null,
        points: Array.isArray(contact.points) ? contact.points : [],
        tool_side: featureIds(contact.tool_side),
        object_side: featureIds(contact.object_side),
      });
    }
  }
}

/** Where each free body's mesh is drawn, and who holds it by the frame. */
function recordBodies(frame) {
  const inFrame = new Map((Array.isArray(frame?.bodies) ? frame.bodies : []).map((b) => [b.name, b]));
  state.bodies = {};
  for (const entry of objects.all()) {
    if (entry.kind !== 'free') continue;
    const body = inFrame.get(entry.name);
    state.bodies[entry.name] = {
      mesh_p: entry.group.position.toArray(),
      held: Boolean(body?.held),
      touching_tools: Array.isArray(body?.touching_tools) ? body.touching_tools.map(String) : [],
    };
  }
}

function featureIds(side) {
  const list = (a) => (Array.isArray(a) ? a : []);
  return { vertices: list(side?.vertices), edges: list(side?.edges), faces: list(side?.faces) };
}

function setServerConnected(connected, message) {
  serverConnected = connected;
  serverMessage = message;
  panel.setBanner('server', connected ? null
    : `Simulation server unavailable: ${message || 'no connection'} (the bridge keeps retrying)`);
  refreshStatus();
}

/** The JSON device pose of `tool` in the latest frame, else where its mesh is. */
function devicePose(tool) {
  const inFrame = latestFrame?.tools?.find?.((t) => t.name === tool);
  if (inFrame?.device) return inFrame.device;
  const entry = objects.get(tool);
  if (!entry) return null;
  const q = entry.group.quaternion;
  return { p: entry.group.position.toArray(), q: [q.w, q.x, q.y, q.z] };
}

/** The selector offers the hello's tools, plus any tool seen in geometry or frames. */
function refreshToolNames() {
  const names = new Set(helloTools);
  for (const entry of objects.all()) if (entry.kind === 'tool') names.add(entry.name);
  for (const tool of latestFrame?.tools ?? []) names.add(tool.name);
  panel.setToolNames([...names]);
}

/** Aims the camera at the driven (else chosen) tool and its contact points; false without one. */
function frameOnTool() {
  const tool = state.heldTool ?? panel.selectedTool();
  const entry = tool ? objects.get(tool) : null;
  if (!entry) return false;
  const box = new THREE.Box3().setFromObject(entry.group);
  for (const contact of state.contacts) {
    if (contact.tool !== tool) continue;
    for (const p of contact.points) {
      if (isFiniteArray(p, 3)) box.expandByPoint(new THREE.Vector3(p[0], p[1], p[2]));
    }
  }
  stage.aimAt(box);
  return true;
}

// ---- status ------------------------------------------------------------------

function refreshStatus() {
  state.connected = Boolean(socket?.isOpen) && serverConnected;
  const f = latestFrame;
  const number = (x, digits) => (Number.isFinite(x) ? x.toFixed(digits) : '–');
  panel.setStatusLine([
    `step rate ${number(f?.step_rate_hz, 0)} Hz`,
    `frame age ${number(f?.age_ms, 0)} ms`,
    `dropped frames ${number(f?.dropped_frames, 0)}`,
    `missed steps ${number(f?.missed_steps, 0)}`,
    connectionText(),
    `driving: ${state.heldTool ?? 'none'}`,
  ].join(' · '));
  state.status = panel.statusText();
}

function connectionText() {
  if (SNAPSHOT) return latestFrame ? 'snapshot' : `snapshot without a frame (${serverMessage})`;
  if (!socket?.isOpen) return 'bridge: not connected';
  if (!serverConnected) return `server: ${serverMessage || 'not connected'}`;
  return `server: ${serverMessage || 'connected'}`;
}

// ---- drawing -----------------------------------------------------------------

/** Puts the latest frame into the 3D scene and records what is drawn. */
function drawFrame() {
  frameDirty = false;
  const drawn = frameView.apply(latestFrame, objects);
  state.highlighted = drawn.highlighted;
  state.arrows = drawn.arrows;
  recordBodies(latestFrame);
  if (latestFrame && state.revision >= 0 && !cameraFramedWithFrame) {
    stage.frameOn(objects.boundingBox());
    cameraFramedWithFrame = true;
  }
}

function updatePanel() {
  panelDirty = false;
  lastPanelUpdate = performance.now();
  panel.showTools(state.tools);
  panel.showBodies(state.bodies);
  panel.showContacts(state.contacts);
}

function renderLoop(now) {
  requestAnimationFrame(renderLoop);
  if (frameDirty) drawFrame();
  stage.render();
  chart.draw();
  if (panelDirty && now - lastPanelUpdate >= PANEL_INTERVAL_MS) updatePanel();
  if (latestFrame && state.revision >= 0 && !document.body.dataset.ready) {
    document.body.dataset.ready = '1';
  }
}

// ---- start -------------------------------------------------------------------

function runLive() {
  socket = new BridgeSocket({
    onOpen: () => {
      panel.setBanner('bridge', null);
      refreshStatus();
      loadGeometry(); // the scene may have changed while we were away
    },
    onClose: () => {
      panel.setBanner('bridge', 'Lost the connection to the viewer bridge; reconnecting every second…');
      drive.connectionLost();
      refreshStatus();
    },
    onMessage: handleMessage,
  });
  socket.connect();
  loadGeometry();
  requestAnimationFrame(renderLoop);
}

async function runSnapshot() {
  document.body.classList.add('snapshot');
  if (!(await loadGeometry())) {
    document.title = 'error';
    document.body.dataset.ready = 'error';
    return;
  }
  try {
    receiveFrame(await fetchJson('/frame'));
  } catch (e) {
    serverMessage = e.message; // e.g. 503: no frame yet; the geometry is drawn alone
  }
  drawFrame();
  stage.frameOn(objects.boundingBox());
  updatePanel();
  chart.draw();
  refreshStatus();
  stage.render();
  // Headless Chromium's --screenshot does not show a WebGL canvas drawn
  // once; the same pixels as a plain image it does.
  await stage.freezeToImage();
  document.body.dataset.ready = '1';
  document.title = 'ready';
}

refreshStatus();
if (SNAPSHOT) runSnapshot();
else runLive();
