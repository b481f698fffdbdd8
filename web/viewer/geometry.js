// Builds the scene's meshes from the bridge's /geometry answer and keeps, per
// object, what the highlights need (the HDS vertex/edge/face arrays).

import * as THREE from 'three';
import { materialColor, PROXY_GHOST } from './colors.js';
import { applyJsonPose } from './pose.js';

/**
 * One object of /geometry, as drawn:
 *   name, kind          as in /geometry ("fixed" | "tool" | "free")
 *   group               the solid mesh, placed at the object's pose
 *                       (tools: moved to their device pose by each frame,
 *                       free bodies to the pose each frame gives them)
 *   proxy               tools only: a translucent copy at the proxy pose,
 *                       hidden until a frame gives one; null otherwise
 *   vertices            flat [x0,y0,z0, ...] in the object frame (metres)
 *   triangles, edges    flat vertex-id triples / pairs, indexed by HDS id
 */
export class SceneObjects {
  constructor(scene) {
    this.root = new THREE.Group();
    scene.add(this.root);
    this.entries = new Map();
    this.solidMaterial = new THREE.MeshStandardMaterial({
      vertexColors: true, roughness: 0.8, metalness: 0.0, side: THREE.DoubleSide,
    });
    this.ghostMaterial = new THREE.MeshStandardMaterial({
      color: PROXY_GHOST, transparent: true, opacity: 0.3, depthWrite: false,
      roughness: 0.9, side: THREE.DoubleSide,
    });
  }

  /** Replaces every mesh with those of a /geometry answer. */
  rebuild(geometry) {
    this.clear();
    for (const json of Array.isArray(geometry.objects) ? geometry.objects : []) {
      const entry = this.buildEntry(json);
      this.entries.set(entry.name, entry);
      this.root.add(entry.group);
      if (entry.proxy) this.root.add(entry.proxy);
    }
    this.root.updateMatrixWorld(true);
  }

  clear() {
    for (const entry of this.entries.values()) {
      this.root.remove(entry.group);
      if (entry.proxy) this.root.remove(entry.proxy);
      entry.mesh.geometry.dispose(); // shared by the proxy copy
    }
    this.entries.clear();
  }

  get(name) {
    return this.entries.get(name) ?? null;
  }

  names() {
    return [...this.entries.keys()];
  }

  all() {
    return this.entries.values();
  }

  /** World bounding box of all solid meshes (empty if there are none). */
  boundingBox() {
    const box = new THREE.Box3();
    this.root.updateMatrixWorld(true);
    for (const entry of this.all()) box.expandByObject(entry.group);
    return box;
  }

  buildEntry(json) {
    const vertices = numberArray(json.vertices);
    const triangles = numberArray(json.triangles);
    const edges = numberArray(json.edges);
    const faceMaterials = numberArray(json.face_materials);

    const meshGeometry = buildMeshGeometry(vertices, triangles, faceMaterials);
    const mesh = new THREE.Mesh(meshGeometry, this.solidMaterial);
    const group = new THREE.Group();
    group.add(mesh);
    applyJsonPose(group, json.pose);

    let proxy = null;
    if (json.kind === 'tool') {
      proxy = new THREE.Group();
      proxy.add(new THREE.Mesh(meshGeometry, this.ghostMaterial));
      proxy.visible = false;
    }
    return {
      name: String(json.name), kind: json.kind, group, proxy, mesh,
      vertices, triangles, edges,
    };
  }
}

function numberArray(a) {
  return Array.isArray(a) ? a : [];
}

/**
 * A non-indexed geometry (three vertices per face, so normals come out flat)
 * whose vertex colours are the face's material colour. Faces with a vertex id
 * out of range are skipped.
 */
function buildMeshGeometry(vertices, triangles, faceMaterials) {
  const vertexCount = Math.floor(vertices.length / 3);
  const validId = (id) => Number.isInteger(id) && id >= 0 && id < vertexCount;
  const positions = [];
  const colors = [];
  const color = new THREE.Color();

  for (let f = 0; 3 * f + 2 < triangles.length; f++) {
    const ids = [triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2]];
    if (!ids.every(validId)) continue;
    color.set(materialColor(faceMaterials[f]));
    for (const id of ids) {
      positions.push(vertices[3 * id], vertices[3 * id + 1], vertices[3 * id + 2]);
      colors.push(color.r, color.g, color.b);
    }
  }

  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  return geometry;
}
