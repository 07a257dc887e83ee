// A physics engine client's world (hapticctrl-mujoco's world_t): its geoms with their poses and
// the held body's contacts as planes, in the base frame beside the arm. The meshes are built
// once per model (when the geoms' shapes change) and only moved after that.
import * as THREE from 'three';

// MuJoCo's mjtGeom numbers, as world_t carries them (a mesh comes as its bounding box).
const PLANE = 0;
const SPHERE = 2;
const CAPSULE = 3;
const ELLIPSOID = 4;
const CYLINDER = 5;
const BOX = 6;
const INFINITE_PLANE_HALF_M = 0.5; // a plane of size 0 is infinite: drawn 1 m across
const CONTACT_SIZE_M = 0.03;
const CONTACT_TOUCHING = 0xff8a3d;
const CONTACT_NEAR = 0x40d0ff;
const HELD_EDGES = 0x2ecc71;

/** A unit-free geometry for one geom, in its own frame (MuJoCo's: z along capsules and cylinders). */
function geometryOf(geom) {
  const [a, b, c] = geom.size;
  switch (geom.type) {
    case PLANE:
      return new THREE.PlaneGeometry(2 * (a || INFINITE_PLANE_HALF_M), 2 * (b || INFINITE_PLANE_HALF_M));
    case SPHERE:
      return new THREE.SphereGeometry(a, 24, 12);
    case CAPSULE:
      return new THREE.CapsuleGeometry(a, 2 * b, 8, 16).rotateX(Math.PI / 2);
    case ELLIPSOID:
      return new THREE.SphereGeometry(1, 24, 12).scale(a, b, c);
    case CYLINDER:
      return new THREE.CylinderGeometry(a, a, 2 * b, 24).rotateX(Math.PI / 2);
    case BOX:
      return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    default:
      return null;
  }
}

/** What decides the meshes: the geoms' shapes and colours (their poses only move them). */
function shapeKey(world) {
  return JSON.stringify(world.geoms.map((g) => [g.type, g.size, g.rgba, g.coupled]));
}

export class WorldView {
  constructor(scene) {
    this.group = new THREE.Group();
    this.contacts = new THREE.Group();
    scene.add(this.group, this.contacts);
    this.key = null;
    this.meshes = [];
    this.planes = [];
  }

  /** Draws `world` (a state frame's world, or null: nothing). */
  update(world) {
    this.group.visible = this.contacts.visible = !!world;
    if (!world) return;
    const key = shapeKey(world);
    if (key !== this.key) this.build(world, key);
    world.geoms.forEach((g, i) => {
      const mesh = this.meshes[i];
      if (!mesh) return;
      mesh.position.set(g.pose[0], g.pose[1], g.pose[2]);
      mesh.quaternion.set(g.pose[3], g.pose[4], g.pose[5], g.pose[6]);
    });
    this.updateContacts(world.contacts);
  }

  build(world, key) {
    this.key = key;
    for (const mesh of this.meshes) mesh?.geometry.dispose();
    this.group.clear();
    this.meshes = world.geoms.map((g) => {
      const geometry = geometryOf(g);
      if (!geometry) return null;
      const [r, gr, b, a] = g.rgba;
      const mesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
        color: new THREE.Color(r, gr, b), roughness: 0.7, transparent: a < 1, opacity: a,
        side: g.type === PLANE ? THREE.DoubleSide : THREE.FrontSide,
      }));
      if (g.coupled) {
        // The body the hand holds: its edges, so that it shows inside the handle's frame.
        mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
          new THREE.LineBasicMaterial({ color: HELD_EDGES })));
      }
      this.group.add(mesh);
      return mesh;
    });
  }

  /** One square per contact: its surface's plane, at `point - distance * normal`. */
  updateContacts(contacts) {
    while (this.planes.length < contacts.length) {
      const plane = new THREE.Mesh(new THREE.PlaneGeometry(CONTACT_SIZE_M, CONTACT_SIZE_M),
        new THREE.MeshBasicMaterial({ color: CONTACT_NEAR, transparent: true, opacity: 0.5,
          side: THREE.DoubleSide, depthTest: false }));
      plane.renderOrder = 9;
      this.planes.push(plane);
      this.contacts.add(plane);
    }
    this.planes.forEach((plane, i) => {
      const c = contacts[i];
      plane.visible = !!c;
      if (!c) return;
      const n = new THREE.Vector3(c.normal[0], c.normal[1], c.normal[2]);
      plane.position.set(c.point[0], c.point[1], c.point[2]).addScaledVector(n, -c.distance);
      plane.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n.normalize());
      plane.material.color.set(c.distance <= 0 ? CONTACT_TOUCHING : CONTACT_NEAR);
    });
  }

  /** Where each geom is drawn now (null: a shape the view does not draw), for tests. */
  drawnPositions() {
    return this.meshes.map((m) => (m ? m.position.toArray() : null));
  }

  /** How many contact planes are drawn now, for tests. */
  drawnContacts() {
    return this.planes.filter((p) => p.visible).length;
  }
}
