// Draws one frame into the 3D scene: tool poses (device solid, proxy ghost),
// free bodies' poses, the contact features of both sides, and the force /
// reversing-vector arrows.

import * as THREE from 'three';
import { FEATURE_COLORS, FORCE_ARROW, REVERSING_ARROW } from './colors.js';
import { applyJsonPose, vectorFromJson } from './pose.js';

// Arrow scales: the force is drawn 2 cm per newton; the reversing vector five
// times its length but never shorter than 5 mm, so a tiny one stays visible.
export const FORCE_SCALE_M_PER_N = 0.02;
export const REVERSING_SCALE = 5;
export const REVERSING_MIN_LENGTH_M = 0.005;

const SIDES = ['tool', 'object'];
const FEATURES = ['vertices', 'edges', 'faces'];

export class FrameView {
  constructor(scene) {
    // layers.tool.vertices, layers.object.faces, ...: one drawable each.
    this.layers = {};
    for (const side of SIDES) {
      this.layers[side] = {};
      for (const feature of FEATURES) {
        const layer = new FeatureLayer(feature, FEATURE_COLORS[side][feature]);
        scene.add(layer.object);
        this.layers[side][feature] = layer;
      }
    }
    this.forceArrows = new ArrowPool(scene, FORCE_ARROW);
    this.reversingArrows = new ArrowPool(scene, REVERSING_ARROW);
  }

  /**
   * Shows `frame` (a "frame" message, or null) over the meshes of `objects`
   * (a SceneObjects). Returns what is drawn now:
   *   { highlighted: {tool_vertices, ..., object_faces}, arrows: {reversing_vector, force} }
   */
  apply(frame, objects) {
    const tools = Array.isArray(frame?.tools) ? frame.tools : [];
    poseTools(tools, objects);
    poseBodies(Array.isArray(frame?.bodies) ? frame.bodies : [], objects);
    return {
      highlighted: this.drawFeatures(tools, objects),
      arrows: {
        force: this.forceArrows.show(forceArrowItems(tools)),
        reversing_vector: this.reversingArrows.show(reversingArrowItems(tools)),
      },
    };
  }

  /** Gathers world positions of every contact feature, by side and kind. */
  drawFeatures(tools, objects) {
    const positions = { tool: newFeatureLists(), object: newFeatureLists() };
    for (const tool of tools) {
      const toolEntry = objects.get(tool.name);
      for (const contact of contactsOf(tool)) {
        collectFeatures(positions.tool, toolEntry, contact.tool_side);
        collectFeatures(positions.object, objects.get(contact.object), contact.object_side);
      }
    }
    const counts = {};
    for (const side of SIDES) {
      for (const feature of FEATURES) {
        const list = positions[side][feature];
        this.layers[side][feature].setPositions(list);
        counts[`${side}_${feature}`] = list.length / FLOATS_PER_FEATURE[feature];
      }
    }
    return counts;
  }
}

export function contactsOf(tool) {
  return Array.isArray(tool?.contacts) ? tool.contacts : [];
}

/** Moves each tool's solid mesh to its device pose and its ghost to its proxy pose. */
function poseTools(tools, objects) {
  for (const entry of objects.all()) {
    if (entry.proxy) entry.proxy.visible = false;
  }
  for (const tool of tools) {
    const entry = objects.get(tool.name);
    if (!entry) continue;
    applyJsonPose(entry.group, tool.device);
    entry.group.updateMatrixWorld(true);
    if (entry.proxy) entry.proxy.visible = applyJsonPose(entry.proxy, tool.proxy);
  }
}

/**
 * Moves each free body's mesh to its pose in the frame; a body the frame
 * does not list stays where it was drawn last.
 */
function poseBodies(bodies, objects) {
  for (const body of bodies) {
    const entry = objects.get(body?.name);
    if (!entry || entry.kind !== 'free') continue;
    if (applyJsonPose(entry.group, body.pose)) entry.group.updateMatrixWorld(true);
  }
}

// ---- contact features ----------------------------------------------------

const FLOATS_PER_FEATURE = { vertices: 3, edges: 6, faces: 9 };

function newFeatureLists() {
  return { vertices: [], edges: [], faces: [] };
}

/**
 * Appends the world positions of one side's feature ids ({vertices, edges,
 * faces}) of `entry`, posed as drawn now. Ids out of range are skipped.
 */
function collectFeatures(out, entry, side) {
  if (!entry || !side) return;
  const ids = (list) => (Array.isArray(list) ? list : []);
  for (const v of ids(side.vertices)) {
    pushWorldVertices(out.vertices, entry, [v]);
  }
  for (const e of ids(side.edges)) {
    if (!Number.isInteger(e) || e < 0 || 2 * e + 1 >= entry.edges.length) continue;
    pushWorldVertices(out.edges, entry, [entry.edges[2 * e], entry.edges[2 * e + 1]]);
  }
  for (const f of ids(side.faces)) {
    if (!Number.isInteger(f) || f < 0 || 3 * f + 2 >= entry.triangles.length) continue;
    const t = entry.triangles;
    pushWorldVertices(out.faces, entry, [t[3 * f], t[3 * f + 1], t[3 * f + 2]]);
  }
}

const scratch = new THREE.Vector3();

/** Pushes all the vertices' world x, y, z, or nothing if any id is invalid. */
function pushWorldVertices(out, entry, vertexIds) {
  const vertexCount = Math.floor(entry.vertices.length / 3);
  if (!vertexIds.every((id) => Number.isInteger(id) && id >= 0 && id < vertexCount)) return;
  for (const id of vertexIds) {
    scratch.fromArray(entry.vertices, 3 * id).applyMatrix4(entry.group.matrixWorld);
    out.push(scratch.x, scratch.y, scratch.z);
  }
}

/**
 * One highlight drawable whose positions are replaced per frame: vertices as
 * Points, edges as LineSegments, faces as a translucent mesh overlay pulled
 * towards the camera with polygonOffset so it does not z-fight the object.
 * Points and edges ignore depth, so features inside a penetration show.
 */
class FeatureLayer {
  constructor(feature, color) {
    const geometry = new THREE.BufferGeometry();
    if (feature === 'vertices') {
      this.object = new THREE.Points(geometry, new THREE.PointsMaterial({
        color, size: 9, sizeAttenuation: false, depthTest: false,
      }));
      this.object.renderOrder = 4;
    } else if (feature === 'edges') {
      this.object = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({
        color, depthTest: false,
      }));
      this.object.renderOrder = 3;
    } else {
      this.object = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
        color, transparent: true, opacity: 0.7, side: THREE.DoubleSide, depthWrite: false,
        polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2,
      }));
      this.object.renderOrder = 2;
    }
    this.object.frustumCulled = false; // positions change every frame
    this.object.visible = false;
  }

  setPositions(positions) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    this.object.geometry.dispose();
    this.object.geometry = geometry;
    this.object.visible = positions.length > 0;
  }
}

// ---- arrows --------------------------------------------------------------

/** One force arrow per tool with a non-zero force, at its device origin. */
function forceArrowItems(tools) {
  const items = [];
  for (const tool of tools) {
    const origin = vectorFromJson(tool.device?.p);
    const force = vectorFromJson(tool.force_n);
    if (!origin || !force || force.length() < 1e-9) continue;
    items.push({ origin, vector: force, length: force.length() * FORCE_SCALE_M_PER_N });
  }
  return items;
}

/**
 * One reversing-vector arrow per contact with a non-zero vector, from the
 * contact's first point (or the tool's device origin if it has none).
 */
function reversingArrowItems(tools) {
  const items = [];
  for (const tool of tools) {
    for (const contact of contactsOf(tool)) {
      const vector = vectorFromJson(contact.reversing_vector_m);
      const firstPoint = Array.isArray(contact.points) ? contact.points[0] : null;
      const origin = vectorFromJson(firstPoint) ?? vectorFromJson(tool.device?.p);
      if (!vector || !origin || vector.length() < 1e-12) continue;
      const length = Math.max(vector.length() * REVERSING_SCALE, REVERSING_MIN_LENGTH_M);
      items.push({ origin, vector, length });
    }
  }
  return items;
}

/** A growing set of ArrowHelpers of one colour, drawn on top of the meshes. */
class ArrowPool {
  constructor(scene, color) {
    this.scene = scene;
    this.color = color;
    this.arrows = [];
  }

  /** Shows one arrow per {origin, vector, length}, hides the rest; true if any shown. */
  show(items) {
    items.forEach((item, i) => {
      const arrow = this.arrows[i] ?? this.addArrow();
      const headLength = 0.25 * item.length;
      arrow.position.copy(item.origin);
      arrow.setDirection(item.vector.clone().normalize());
      arrow.setLength(item.length, headLength, 0.5 * headLength);
      arrow.visible = true;
    });
    for (let i = items.length; i < this.arrows.length; i++) this.arrows[i].visible = false;
    return items.length > 0;
  }

  addArrow() {
    const arrow = new THREE.ArrowHelper(
      new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, this.color);
    for (const part of [arrow.line, arrow.cone]) {
      part.material.depthTest = false;
      part.renderOrder = 5;
    }
    this.scene.add(arrow);
    this.arrows.push(arrow);
    return arrow;
  }
}
