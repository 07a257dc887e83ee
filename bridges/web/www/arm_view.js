// The 3D view: the arm drawn from the model's kinematics and the live joint angles, the handle
// frame, the operator's and the rendered wrench (forces) as arrows, the demo's two spheres and
// their contact force, a physics engine client's world (world_view.js). Base frame, z up, metres.
import * as THREE from 'three';
import { OrbitControls } from './vendor/three/controls/OrbitControls.js';
import { forwardKinematics } from './kinematics.js';
import { WorldView } from './world_view.js';

const SMALLEST_ARROW_N = 0.05;
const MIN_RENDER_INTERVAL_MS = 40; // at most 25 frames a second
const MOBILE_FREE = 0x2ecc71; // the demo's sphere coupled to the handle
const SURFACE_COLOUR = 0x3fa9f5; // the surface rendered on the handle (J2)
const SURFACE_SIZE_M = 0.1;
const MOBILE_TOUCHING = 0xff8a3d;
/** After the rendered surface's plane (order 0), so that nothing is blended over an arrow. */
const ARROW_RENDER_ORDER = 10;
const COLOURS = { operator: 0xf0c040, rendered: 0xff4fd8, contact: 0x40d0ff };

function vec(a) {
  return new THREE.Vector3(a[0], a[1], a[2]);
}

/** A unit cylinder along y, stretched between two points. */
function placeBetween(mesh, from, to) {
  const direction = new THREE.Vector3().subVectors(to, from);
  const length = direction.length();
  mesh.visible = length > 1e-6;
  if (!mesh.visible) return;
  mesh.position.copy(from).addScaledVector(direction, 0.5);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), direction.normalize());
  mesh.scale.set(1, length, 1);
}

/**
 * An arrow's length (m) for a force (N): 4 cm, and 4 cm more for each doubling of 1 N + the
 * force, so that 0.5 N (6.3 cm) reaches out of the demo's 3 cm sphere and 35 N (24.5 cm) stays
 * in the view. At 1 cm per newton 0.5 N drew 5 mm, inside the sphere, and 35 N ran off the
 * view (J8's walk-through). The legend says the scale.
 */
export function arrowLength(newtons) {
  return 0.04 + 0.04 * Math.log2(1 + newtons);
}

function setArrow(arrow, origin, force) {
  const f = vec(force);
  const magnitude = f.length();
  arrow.visible = magnitude >= SMALLEST_ARROW_N;
  if (!arrow.visible) return;
  const length = arrowLength(magnitude);
  arrow.position.copy(origin);
  arrow.setDirection(f.normalize());
  arrow.setLength(length, Math.min(0.04, length * 0.4), Math.min(0.024, length * 0.25));
}

export class ArmView {
  /** Throws when WebGL is unavailable; the caller shows the rest of the page anyway. */
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x0b0d10);
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 20);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(1.05, -1.05, 0.75);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.target.set(0.35, 0, 0.2);
    this.controls.update();
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(1, -1, 2);
    this.scene.add(sun);
    const grid = new THREE.GridHelper(1.6, 16, 0x3a4350, 0x262c35);
    grid.rotation.x = Math.PI / 2; // into the base's xy plane
    this.scene.add(grid);
    this.scene.add(new THREE.AxesHelper(0.15));
    this.arm = new THREE.Group();
    this.scene.add(this.arm);
    this.handleAxes = new THREE.AxesHelper(0.08);
    this.scene.add(this.handleAxes);
    this.arrows = {};
    for (const [name, colour] of Object.entries(COLOURS)) {
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 0.1, colour);
      // Drawn over everything: the handle sits inside the demo's 3 cm sphere, which hid every
      // force under 3 N and the base of the larger ones. Drawn last, too: three.js draws opaque
      // objects before transparent ones whatever their renderOrder (which a parent does not pass
      // to its children), so the rendered surface's translucent plane was blended over an arrow
      // behind it (2 of 180 pixels at 6.75 N, CI, 2026-12-05): transparent at full opacity, the
      // arrows sort after it.
      for (const part of [arrow.line, arrow.cone]) {
        Object.assign(part.material, { depthTest: false, transparent: true, opacity: 1 });
        part.renderOrder = ARROW_RENDER_ORDER;
      }
      arrow.visible = false;
      this.arrows[name] = arrow;
      this.scene.add(arrow);
    }
    this.fixedSphere = new THREE.Mesh(new THREE.SphereGeometry(1, 32, 16),
      new THREE.MeshStandardMaterial({ color: 0x8a8f98, roughness: 0.6 }));
    this.mobileSphere = new THREE.Mesh(new THREE.SphereGeometry(1, 32, 16),
      new THREE.MeshStandardMaterial({ color: MOBILE_FREE, roughness: 0.4 }));
    this.mobileSphere.add(new THREE.AxesHelper(1.3)); // shows the sphere's rotation
    this.fixedSphere.visible = this.mobileSphere.visible = false;
    this.scene.add(this.fixedSphere, this.mobileSphere);
    // The surface the controller renders on the handle in its servo cycle (J2): a square of the
    // plane through its point, drawn through the scene's spheres like the arrows.
    this.surface = new THREE.Mesh(new THREE.PlaneGeometry(SURFACE_SIZE_M, SURFACE_SIZE_M),
      new THREE.MeshBasicMaterial({ color: SURFACE_COLOUR, transparent: true, opacity: 0.35,
        side: THREE.DoubleSide, depthWrite: false }));
    this.surface.add(new THREE.LineSegments(
      new THREE.EdgesGeometry(new THREE.PlaneGeometry(SURFACE_SIZE_M, SURFACE_SIZE_M)),
      new THREE.LineBasicMaterial({ color: SURFACE_COLOUR })));
    this.surface.visible = false;
    this.scene.add(this.surface);
    this.world = new WorldView(this.scene);
    this.framesRendered = 0;
    // Render on demand (new telemetry, camera moved, resize), not at the display's full rate:
    // software WebGL on the controller's own host would otherwise take CPU from the cycle
    // (headless chromium with SwiftShader drawing every animation frame: 112 % of a vCPU on the
    // 2-vCPU CI VM, 2026-12-01).
    this.dirty = true;
    this.controls.addEventListener('change', () => { this.dirty = true; });
    new ResizeObserver(() => this.resize()).observe(canvas.parentElement);
    this.resize();
    let lastRender = 0;
    const loop = (now) => {
      if (this.dirty && now - lastRender >= MIN_RENDER_INTERVAL_MS) {
        this.dirty = false;
        lastRender = now;
        this.renderer.render(this.scene, this.camera);
        this.framesRendered += 1;
      }
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.canvas.parentElement;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  /** Builds the links and joints for a model ({"type":"model"} from the bridge). */
  setModel(model) {
    this.model = model;
    this.dirty = true;
    this.arm.clear();
    const linkMaterial = new THREE.MeshStandardMaterial({ color: 0xc7ccd4, metalness: 0.3, roughness: 0.5 });
    const jointMaterial = new THREE.MeshStandardMaterial({ color: 0x5a6b82, roughness: 0.5 });
    this.links = [];
    this.joints = [];
    for (let i = 0; i <= model.joints.length; i += 1) {
      const link = new THREE.Mesh(new THREE.CylinderGeometry(0.014, 0.014, 1, 16), linkMaterial);
      this.links.push(link);
      this.arm.add(link);
    }
    for (let i = 0; i < model.joints.length; i += 1) {
      const joint = new THREE.Mesh(new THREE.SphereGeometry(0.02, 20, 12), jointMaterial);
      this.joints.push(joint);
      this.arm.add(joint);
    }
    const ws = model.workspace;
    if (ws && ws.half_size.every((h) => h > 0)) {
      const box = new THREE.LineSegments(
        new THREE.EdgesGeometry(new THREE.BoxGeometry(2 * ws.half_size[0], 2 * ws.half_size[1], 2 * ws.half_size[2])),
        new THREE.LineBasicMaterial({ color: 0x4a5566 }));
      box.position.copy(vec(ws.center));
      this.arm.add(box);
    }
  }

  /** Moves everything to a state frame ({"type":"state"}). */
  update(frame) {
    this.dirty = true;
    const arm = frame.arm;
    if (this.model && arm) {
      const chain = forwardKinematics(this.model, arm.joint_position);
      const points = [[0, 0, 0], ...chain.joints, chain.handle].map(vec);
      this.links.forEach((link, i) => placeBetween(link, points[i], points[i + 1]));
      this.joints.forEach((joint, i) => joint.position.copy(points[i + 1]));
    }
    if (arm) {
      const p = arm.handle_pose;
      const handle = vec(p);
      this.handleAxes.position.copy(handle);
      this.handleAxes.quaternion.set(p[3], p[4], p[5], p[6]);
      setArrow(this.arrows.operator, handle, arm.operator_wrench);
      setArrow(this.arrows.rendered, handle, arm.rendered_wrench);
    }
    this.updateScene(frame.scene);
    this.world.update(frame.world);
    this.updateSurface(frame.coupling);
  }

  /** The rendered surface's plane, when there is one (its normal is not zero). */
  updateSurface(coupling) {
    const n = coupling?.surface_normal;
    const normal = n ? new THREE.Vector3(n[0], n[1], n[2]) : new THREE.Vector3();
    this.surface.visible = normal.lengthSq() > 0.5;
    if (!this.surface.visible) return;
    this.surface.position.copy(vec(coupling.surface_point));
    this.surface.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal.normalize());
    this.surface.material.opacity = coupling.surface_force > 0 ? 0.55 : 0.25;
  }

  updateScene(scene) {
    this.fixedSphere.visible = this.mobileSphere.visible = !!scene;
    if (!scene) {
      this.arrows.contact.visible = false;
      return;
    }
    this.fixedSphere.position.copy(vec(scene.fixed_center));
    this.fixedSphere.scale.setScalar(scene.fixed_radius);
    const m = scene.mobile_pose;
    this.mobileSphere.position.set(m[0], m[1], m[2]);
    this.mobileSphere.quaternion.set(m[3], m[4], m[5], m[6]);
    this.mobileSphere.scale.setScalar(scene.mobile_radius);
    const touching = scene.penetration > 0;
    this.mobileSphere.material.color.set(touching ? MOBILE_TOUCHING : MOBILE_FREE);
    const towardsMobile = new THREE.Vector3().subVectors(this.mobileSphere.position, this.fixedSphere.position);
    const contactPoint = this.fixedSphere.position.clone()
      .addScaledVector(towardsMobile.normalize(), scene.fixed_radius);
    setArrow(this.arrows.contact, contactPoint, touching ? scene.contact_force : [0, 0, 0]);
  }
}
