// Driving a tool from this page: take / release, mouse and keyboard moves,
// and the throttled stream of "pose" messages while a tool is held.
//
// While a tool is held:
//   left-drag          translates it in the view plane (the plane facing the
//                      camera through the tool's position, grab point kept)
//   Shift + left-drag  rotates it (horizontal: about the camera's up axis,
//                      vertical: about the camera's right axis)
//   arrow keys         1 mm along the camera's up / right axes
//   PageUp / PageDown  1 mm toward / away from the camera
//   R or Escape        releases; T takes the selected tool
// The camera (OrbitControls) is disabled during a drag, and camera moves never
// move the tool.

import * as THREE from 'three';
import { poseFromJson, poseToJson, vectorFromJson } from './pose.js';

const POSE_INTERVAL_MS = 1000 / 60; // at most ~60 poses per second
const KEY_STEP_M = 0.001;
const ROTATE_RAD_PER_PX = 0.01;
const MOVE_BY_STEPS = 10;
const MOVE_BY_DURATION_MS = 200;
const ANSWER_TIMEOUT_MS = 5000;

export class DriveControls {
  /**
   * canvas, camera, orbit  the 3D view (orbit: OrbitControls)
   * send(message)          to the bridge; returns false if not connected
   * devicePose(tool)       {p, q} JSON pose of the tool now, or null
   * selectedTool()         the tool chosen in the panel
   * state                  window.viewerState (heldTool, driveState, posesSent)
   * onChange()             called when what is held or the drive state changes
   */
  constructor({ canvas, camera, orbit, send, devicePose, selectedTool, state, onChange }) {
    Object.assign(this, { canvas, camera, orbit, send, devicePose, selectedTool, state, onChange });
    this.drivePose = null;   // {position, quaternion} this page commands, while held
    this.requestedTool = null; // the tool of the last take, until answered
    this.drag = null;
    this.waiters = [];       // promises of take/release waiting for a "drive" answer
    this.message = '';       // the last "drive" message text
    this.throttle = new PoseThrottle((message) => {
      if (this.send(message)) this.state.posesSent++;
    });

    // Capture phase: runs before OrbitControls' own pointerdown on the canvas,
    // so a tool drag can disable the camera before it starts to orbit.
    canvas.addEventListener('pointerdown', (e) => this.onPointerDown(e), { capture: true });
    canvas.addEventListener('pointermove', (e) => this.onPointerMove(e));
    canvas.addEventListener('pointerup', (e) => this.endDrag(e));
    canvas.addEventListener('pointercancel', (e) => this.endDrag(e));
    window.addEventListener('keydown', (e) => this.onKeyDown(e));
  }

  /** Asks to become `tool`'s device; resolves with the answer's state. */
  take(tool) {
    if (!tool) return Promise.resolve('no tool');
    if (this.state.heldTool && this.state.heldTool !== tool) this.release();
    this.requestedTool = tool;
    if (!this.send({ type: 'take', tool })) return Promise.resolve('not connected');
    this.setDriveState('taking', '');
    return this.answerFor(tool);
  }

  /** Gives the held tool back; resolves with the answer's state. */
  release() {
    const tool = this.state.heldTool ?? this.requestedTool;
    if (!tool) return Promise.resolve(this.state.driveState);
    this.throttle.flush(); // the last pose still goes out first
    this.stopDriving();
    this.requestedTool = null;
    if (!this.send({ type: 'release', tool })) return Promise.resolve('not connected');
    this.setDriveState('releasing', '');
    return this.answerFor(tool);
  }

  /**
   * Moves the held tool by a world offset [dx, dy, dz] (metres) in equal steps
   * over ~200 ms; resolves once the last pose is sent.
   */
  async moveBy(offset) {
    const total = vectorFromJson(offset);
    if (!total) throw new Error('moveBy takes [dx, dy, dz] in metres');
    if (!this.drivePose) throw new Error('no tool is held');
    const step = total.divideScalar(MOVE_BY_STEPS);
    for (let i = 0; i < MOVE_BY_STEPS; i++) {
      if (!this.drivePose) throw new Error('the tool was released during moveBy');
      this.drivePose.position.add(step);
      this.sendPose();
      await sleep(MOVE_BY_DURATION_MS / MOVE_BY_STEPS);
    }
    this.throttle.flush();
  }

  /** A "drive" message from the bridge. */
  handleDrive(message) {
    const tool = String(message.tool ?? '');
    const driveState = String(message.state ?? '');
    if (driveState === 'held') {
      // Start from where the tool is now, so taking it does not make it jump.
      const pose = poseFromJson(this.devicePose(tool));
      this.state.heldTool = tool;
      this.drivePose = pose ?? { position: new THREE.Vector3(), quaternion: new THREE.Quaternion() };
      // Where it is now goes out at once: the bridge keeps sending the
      // last pose while the user holds still, and the server releases a
      // tool whose device is silent.
      if (pose) this.sendPose();
    } else if (tool === this.state.heldTool) {
      this.stopDriving(); // released (by us or the bridge) or refused
    }
    if (tool === this.requestedTool) this.requestedTool = null;
    this.setDriveState(driveState, String(message.message ?? ''));
    this.settleWaiters(tool, driveState);
  }

  /** The WebSocket closed: the bridge drops our drive with it. */
  connectionLost() {
    const tool = this.state.heldTool ?? this.requestedTool;
    this.stopDriving();
    this.requestedTool = null;
    if (tool) {
      this.setDriveState('released', 'connection to the bridge lost');
      this.settleWaiters(tool, 'released');
    }
  }

  // ---- internals ---------------------------------------------------------

  stopDriving() {
    this.throttle.cancel();
    this.drivePose = null;
    this.state.heldTool = null;
    this.cancelDrag();
  }

  setDriveState(driveState, message) {
    this.state.driveState = driveState;
    this.message = message;
    this.onChange();
  }

  answerFor(tool) {
    return new Promise((resolve) => {
      const waiter = { tool, resolve };
      this.waiters.push(waiter);
      setTimeout(() => this.settle(waiter, 'timeout'), ANSWER_TIMEOUT_MS);
    });
  }

  settleWaiters(tool, answer) {
    for (const waiter of this.waiters.filter((w) => w.tool === tool)) this.settle(waiter, answer);
  }

  settle(waiter, answer) {
    const i = this.waiters.indexOf(waiter);
    if (i < 0) return;
    this.waiters.splice(i, 1);
    waiter.resolve(answer);
  }

  /** Queues the drive pose for sending (finite numbers, unit quaternion). */
  sendPose() {
    const pose = this.drivePose;
    if (!pose || !this.state.heldTool) return;
    pose.quaternion.normalize();
    const json = poseToJson(pose);
    if (![...json.p, ...json.q].every(Number.isFinite)) return;
    this.throttle.push({ type: 'pose', tool: this.state.heldTool, ...json });
  }

  // ---- mouse ---------------------------------------------------------------

  onPointerDown(e) {
    if (e.button !== 0 || !this.drivePose) return;
    this.orbit.enabled = false;
    this.canvas.setPointerCapture(e.pointerId);
    e.preventDefault();
    this.drag = { pointerId: e.pointerId, rotate: e.shiftKey, x: e.clientX, y: e.clientY };
    if (!this.drag.rotate) {
      // The view plane: faces the camera, through the tool's position.
      const normal = this.camera.getWorldDirection(new THREE.Vector3());
      this.drag.plane = new THREE.Plane().setFromNormalAndCoplanarPoint(
        normal, this.drivePose.position);
      const hit = this.pointOnPlane(e, this.drag.plane);
      this.drag.offset = hit ? this.drivePose.position.clone().sub(hit) : new THREE.Vector3();
    }
  }

  onPointerMove(e) {
    const drag = this.drag;
    if (!drag || e.pointerId !== drag.pointerId || !this.drivePose) return;
    if (drag.rotate) {
      const { up, right } = this.cameraAxes();
      const turn = new THREE.Quaternion()
        .setFromAxisAngle(up, (e.clientX - drag.x) * ROTATE_RAD_PER_PX)
        .multiply(new THREE.Quaternion().setFromAxisAngle(right, (e.clientY - drag.y) * ROTATE_RAD_PER_PX));
      this.drivePose.quaternion.premultiply(turn);
    } else {
      const hit = this.pointOnPlane(e, drag.plane);
      if (!hit) return;
      this.drivePose.position.copy(hit.add(drag.offset));
    }
    drag.x = e.clientX;
    drag.y = e.clientY;
    this.sendPose();
  }

  endDrag(e) {
    if (!this.drag || e.pointerId !== this.drag.pointerId) return;
    this.cancelDrag();
  }

  cancelDrag() {
    if (!this.drag) return;
    if (this.canvas.hasPointerCapture(this.drag.pointerId)) {
      this.canvas.releasePointerCapture(this.drag.pointerId);
    }
    this.drag = null;
    this.orbit.enabled = true;
  }

  /** Where the mouse ray meets `plane`, or null (ray parallel to it). */
  pointOnPlane(e, plane) {
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((e.clientX - rect.left) / rect.width) * 2 - 1,
      -((e.clientY - rect.top) / rect.height) * 2 + 1);
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    return raycaster.ray.intersectPlane(plane, new THREE.Vector3());
  }

  /** The camera's screen axes in world coordinates, and its viewing direction. */
  cameraAxes() {
    const q = this.camera.quaternion;
    return {
      up: new THREE.Vector3(0, 1, 0).applyQuaternion(q),
      right: new THREE.Vector3(1, 0, 0).applyQuaternion(q),
      forward: this.camera.getWorldDirection(new THREE.Vector3()),
    };
  }

  // ---- keyboard ------------------------------------------------------------

  onKeyDown(e) {
    if (e.ctrlKey || e.metaKey || e.altKey) return; // leave browser shortcuts alone
    const key = e.key.length === 1 ? e.key.toLowerCase() : e.key;
    if (key === 't') {
      this.take(this.selectedTool());
    } else if (key === 'r' || key === 'Escape') {
      this.release();
    } else {
      const inSelect = e.target instanceof HTMLSelectElement; // arrows change the choice
      if (inSelect || !this.drivePose || !this.keyStep(key)) return;
    }
    e.preventDefault();
  }

  /** Moves the held tool 1 mm for an arrow / page key; false for other keys. */
  keyStep(key) {
    const { up, right, forward } = this.cameraAxes();
    const directions = {
      ArrowUp: up, ArrowDown: up.clone().negate(),
      ArrowRight: right, ArrowLeft: right.clone().negate(),
      PageUp: forward.clone().negate(), PageDown: forward,
    };
    const direction = directions[key];
    if (!direction) return false;
    this.drivePose.position.addScaledVector(direction, KEY_STEP_M);
    this.sendPose();
    return true;
  }
}

/**
 * Sends the newest message at most once per POSE_INTERVAL_MS: a message that
 * comes too soon waits, and is replaced if a newer one arrives meanwhile.
 */
class PoseThrottle {
  constructor(send) {
    this.send = send;
    this.pending = null;
    this.timer = null;
    this.lastSent = -Infinity;
  }

  push(message) {
    this.pending = message;
    if (this.timer) return;
    const wait = this.lastSent + POSE_INTERVAL_MS - performance.now();
    if (wait <= 0) this.flush();
    else this.timer = setTimeout(() => this.flush(), wait);
  }

  /** Sends the waiting message now, if any. */
  flush() {
    clearTimeout(this.timer);
    this.timer = null;
    if (!this.pending) return;
    this.lastSent = performance.now();
    this.send(this.pending);
    this.pending = null;
  }

  cancel() {
    clearTimeout(this.timer);
    this.timer = null;
    this.pending = null;
  }
}

function sleep(ms) {
  return new Promise((resolve) => setTimeout(resolve, ms));
}
