// The 3D stage: renderer, z-up camera with OrbitControls, lights, and a floor
// grid sized to the scene.
//
// Camera: left-drag orbits (when no tool is held; see controls.js), middle-drag
// orbits, right-drag pans, the wheel zooms.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { BACKGROUND, GRID_MAJOR, GRID_MINOR } from './colors.js';

const VIEW_DIRECTION = new THREE.Vector3(0.8, -1.2, 0.7).normalize(); // from the target
const GRID_DIVISIONS = 20;
const MIN_FRAMED_RADIUS_M = 0.01;

export class Stage {
  /**
   * Throws if WebGL is not available. `keepDrawing`: keep the drawn image
   * after it is shown (a headless screenshot reads it later).
   */
  constructor(container, keepDrawing = false) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: keepDrawing });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.prepend(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(BACKGROUND);
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.9));
    const key = new THREE.DirectionalLight(0xffffff, 2.2);
    key.position.set(1, -1.5, 2);
    const fill = new THREE.DirectionalLight(0xffffff, 0.7);
    fill.position.set(-1.5, 1, 0.5);
    this.scene.add(key, fill);

    this.camera = new THREE.PerspectiveCamera(45, 1, 0.001, 100);
    this.camera.up.set(0, 0, 1); // z up; must be set before OrbitControls
    this.orbit = new OrbitControls(this.camera, this.renderer.domElement);
    this.orbit.mouseButtons = {
      LEFT: THREE.MOUSE.ROTATE, MIDDLE: THREE.MOUSE.ROTATE, RIGHT: THREE.MOUSE.PAN,
    };
    this.grid = null;
    this.frameOn(new THREE.Box3());

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  get canvas() {
    return this.renderer.domElement;
  }

  resize() {
    const width = Math.max(1, this.container.clientWidth);
    const height = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(width, height);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
  }

  render() {
    this.orbit.update();
    this.renderer.render(this.scene, this.camera);
  }

  /** Replaces the canvas by an image of what it shows (needs keepDrawing). */
  async freezeToImage() {
    const canvas = this.renderer.domElement;
    const image = new Image();
    image.src = canvas.toDataURL('image/png');
    await image.decode();
    image.style.width = canvas.style.width || `${canvas.clientWidth}px`;
    image.style.height = canvas.style.height || `${canvas.clientHeight}px`;
    image.style.display = 'block';
    canvas.replaceWith(image);
  }

  /**
   * Points the camera at a world box (an empty box: 10 cm around the origin)
   * and lays the floor grid under it.
   */
  frameOn(box) {
    const sphere = this.aimAt(box);
    this.placeGrid(sphere.center, sphere.radius, box.isEmpty() ? 0 : box.min.z);
  }

  /**
   * Points the camera at a world box from the usual direction, near enough
   * that the box fills the view; the grid stays where it is. Returns the
   * sphere framed.
   */
  aimAt(box) {
    const sphere = box.isEmpty()
      ? new THREE.Sphere(new THREE.Vector3(), 0.1)
      : box.getBoundingSphere(new THREE.Sphere());
    sphere.radius = Math.max(sphere.radius, MIN_FRAMED_RADIUS_M);
    const halfFov = THREE.MathUtils.degToRad(this.camera.fov / 2);
    const distance = (1.15 * sphere.radius) / Math.sin(halfFov);

    this.camera.position.copy(sphere.center).addScaledVector(VIEW_DIRECTION, distance);
    this.camera.near = distance / 1000;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.orbit.target.copy(sphere.center);
    this.orbit.update();
    return sphere;
  }

  /** Where the camera looks and from how far (metres), for viewerState. */
  view() {
    return {
      target: this.orbit.target.toArray(),
      distance: this.camera.position.distanceTo(this.orbit.target),
    };
  }

  /** A floor grid under the scene; its spacing is the power of ten nearest radius / 5. */
  placeGrid(center, radius, floorZ) {
    if (this.grid) {
      this.scene.remove(this.grid);
      this.grid.geometry.dispose();
      this.grid.material.dispose();
    }
    const spacing = 10 ** Math.round(Math.log10(radius / 5));
    this.grid = new THREE.GridHelper(
      spacing * GRID_DIVISIONS, GRID_DIVISIONS, GRID_MAJOR, GRID_MINOR);
    this.grid.rotation.x = Math.PI / 2; // GridHelper lies in XZ; the floor is XY
    this.grid.position.set(center.x, center.y, floorZ);
    this.scene.add(this.grid);
  }
}
