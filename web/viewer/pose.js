// Conversions between the bridge's JSON poses and three.js objects.
// JSON: positions are [x, y, z] in metres, quaternions [w, x, y, z] (world
// frame, z up). three.js quaternions are (x, y, z, w).

import * as THREE from 'three';

/** True if `a` is an array of `n` finite numbers. */
export function isFiniteArray(a, n) {
  return Array.isArray(a) && a.length === n && a.every(Number.isFinite);
}

/** [x, y, z] -> Vector3, or null if not three finite numbers. */
export function vectorFromJson(a) {
  return isFiniteArray(a, 3) ? new THREE.Vector3(a[0], a[1], a[2]) : null;
}

/** [w, x, y, z] -> normalised Quaternion, or null if invalid or zero. */
export function quaternionFromJson(a) {
  if (!isFiniteArray(a, 4)) return null;
  const q = new THREE.Quaternion(a[1], a[2], a[3], a[0]);
  return q.length() > 1e-9 ? q.normalize() : null;
}

/** {"p":[..],"q":[..]} -> {position, quaternion}, or null if invalid. */
export function poseFromJson(pose) {
  const position = vectorFromJson(pose?.p);
  const quaternion = quaternionFromJson(pose?.q);
  return position && quaternion ? { position, quaternion } : null;
}

/** Places an Object3D at a JSON pose; returns false (and leaves it) if invalid. */
export function applyJsonPose(object, jsonPose) {
  const pose = poseFromJson(jsonPose);
  if (!pose) return false;
  object.position.copy(pose.position);
  object.quaternion.copy(pose.quaternion);
  return true;
}

/** {position, quaternion} -> the fields of a "pose" message ({p, q}). */
export function poseToJson(pose) {
  const q = pose.quaternion.clone().normalize();
  return {
    p: pose.position.toArray(),
    q: [q.w, q.x, q.y, q.z],
  };
}
