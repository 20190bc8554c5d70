// wqmesh page: the three.js view. One merged indexed BufferGeometry for the
// drawn tets (opaque group first, then the faded group), a vertex shader that
// shrinks every drawn tet towards its centroid (uniform `shrink`), line
// overlays for the tet edges, the input surface preview with its sharp
// edges and vertices, the error highlight, protecting balls, pumped vertices
// and the picked tet. Renders on demand (no animation loop).
// SPDX-License-Identifier: GPL-3.0-or-later
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const SHRINK_VERTEX = `
attribute vec3 tetCentroid;
uniform float shrink;
`;

function shrinkMaterial(material, shrink) {
  material.onBeforeCompile = (shader) => {
    shader.uniforms.shrink = shrink;
    shader.vertexShader = SHRINK_VERTEX + shader.vertexShader.replace(
      '#include <begin_vertex>',
      'vec3 transformed = tetCentroid + (position - tetCentroid) * shrink;');
  };
  return material;
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: false });
    this.renderer.setPixelRatio(Math.min(2, globalThis.devicePixelRatio || 1));
    this.renderer.setClearColor(0xf4f6f8, 1);
    this.canvas = this.renderer.domElement;
    this.canvas.setAttribute('aria-label', 'Mesh view: drag to rotate, scroll to zoom, click a tet to pick it');
    this.canvas.tabIndex = 0;
    container.appendChild(this.canvas);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
    this.camera.position.set(2, -3, 2);
    this.camera.up.set(0, 0, 1);
    this.scene.add(this.camera);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0xa0acb8, 1.7));
    const light = new THREE.DirectionalLight(0xffffff, 1.5);
    light.position.set(1, 2, 3);
    this.camera.add(light);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.render());
    this.controls.listenToKeyEvents?.(this.canvas);
    this.shrink = { value: 1 };
    this.size = 1;
    this.groups = {
      surface: new THREE.Group(), mesh: new THREE.Group(), overlay: new THREE.Group(), marker: new THREE.Group(),
    };
    for (const g of Object.values(this.groups)) this.scene.add(g);
    this.opaque = shrinkMaterial(new THREE.MeshPhongMaterial({
      vertexColors: true, flatShading: true, shininess: 10, polygonOffset: true, polygonOffsetFactor: 1,
      polygonOffsetUnits: 1 }), this.shrink);
    this.faded = shrinkMaterial(new THREE.MeshPhongMaterial({
      vertexColors: true, flatShading: true, transparent: true, opacity: 0.12, depthWrite: false }), this.shrink);
    this.edgeMaterial = shrinkMaterial(new THREE.LineBasicMaterial({ color: 0x223344, transparent: true, opacity: 0.35 }),
                                       this.shrink);
    this.meshObject = null;
    this.faceTet = null;
    this.pending = false;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    this.warmUp();
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  /** Schedules one frame (several calls in one task give one frame). */
  render() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
      const w = this.frameWaiters || [];
      this.frameWaiters = [];
      for (const r of w) r();
    });
  }

  /** Resolves after the next frame is drawn. */
  nextFrame() {
    return new Promise((resolve) => {
      (this.frameWaiters ||= []).push(resolve);
      this.render();
    });
  }

  /**
   * Compiles the shaders of every material once, at start-up: with a
   * software GL a first compile takes a few hundred ms, which must not
   * happen during a run.
   */
  warmUp() {
    // In the real scene (its lights are part of every program's key).
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(9), 3));
    g.setAttribute('tetCentroid', new THREE.BufferAttribute(new Float32Array(9), 3));
    g.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(9), 3, true));
    g.setIndex(new THREE.BufferAttribute(new Uint32Array([0, 1, 2]), 1));
    const group = new THREE.Group();
    const mesh = new THREE.Mesh(g, [this.opaque, this.faded]);
    g.addGroup(0, 3, 0);
    g.addGroup(0, 3, 1);
    group.add(mesh, new THREE.LineSegments(g, this.edgeMaterial));
    for (const m of this.surfaceMaterials()) {
      group.add(m.isPointsMaterial ? new THREE.Points(g, m) : m.isLineBasicMaterial ? new THREE.LineSegments(g, m)
        : new THREE.Mesh(g, m));
    }
    const ball = new THREE.InstancedMesh(new THREE.SphereGeometry(1, 4, 4), this.mats.balls, 1);
    group.add(ball);
    this.scene.add(group);
    this.renderer.compile(this.scene, this.camera);
    this.renderer.render(this.scene, this.camera);
    this.scene.remove(group);
    g.dispose();
    ball.geometry.dispose();
    ball.dispose();
  }

  /** The materials of the preview (made once, shared by every preview). */
  surfaceMaterials() {
    if (!this.mats) {
      this.mats = {
        surface: new THREE.MeshPhongMaterial({ color: 0xb8c4d2, flatShading: true, side: THREE.DoubleSide, shininess: 10,
          polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }),
        feature: new THREE.LineBasicMaterial({ color: 0x33414f }),
        sharp: new THREE.LineBasicMaterial({ color: 0xd7191c, depthTest: false }),
        sharpPoints: new THREE.PointsMaterial({ color: 0xd7191c, size: 9, sizeAttenuation: false, depthTest: false }),
        bad: new THREE.MeshBasicMaterial({ color: 0xff2d55, side: THREE.DoubleSide, depthTest: false, transparent: true, opacity: 0.8 }),
        badEdge: new THREE.LineBasicMaterial({ color: 0xff00aa, depthTest: false }),
        badPoints: new THREE.PointsMaterial({ color: 0xff00aa, size: 12, sizeAttenuation: false, depthTest: false }),
        marker: new THREE.LineBasicMaterial({ color: 0x00a878, depthTest: false }),
        balls: new THREE.MeshPhongMaterial({ color: 0x2b83ba, transparent: true, opacity: 0.25, depthWrite: false }),
        pumped: new THREE.PointsMaterial({ color: 0x008837, size: 6, sizeAttenuation: false, depthTest: false }),
      };
    }
    return Object.values(this.mats);
  }

  /** Renders now and returns the picture as a PNG Blob. */
  screenshot() {
    this.renderer.render(this.scene, this.camera);
    return new Promise((resolve) => this.canvas.toBlob(resolve, 'image/png'));
  }

  clear(group) {
    const g = this.groups[group];
    for (const o of [...g.children]) {
      g.remove(o);
      o.geometry?.dispose();

    }
    if (group === 'mesh') { this.meshObject = null; this.faceTet = null; }
    this.render();
  }

  /** Frames a box of the given size around the origin (all positions are relative to the model's center). */
  frame(size) {
    this.size = size || 1;
    const d = this.size * 2.4;
    this.camera.near = this.size / 100;
    this.camera.far = this.size * 100;
    // From +x, -y and above: the cut of the default plane (normal x, the
    // side x <= c kept) faces the camera.
    this.camera.position.set(d * 0.8, -d * 0.55, d * 0.5);
    this.controls.target.set(0, 0, 0);
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.render();
  }

  showSurface(s) {
    this.clear('surface');
    const g = this.groups.surface;
    this.surfaceMaterials();
    const M = this.mats;
    const geometry = (arr) => {
      const geom = new THREE.BufferGeometry();
      geom.setAttribute('position', new THREE.BufferAttribute(arr, 3));
      return geom;
    };
    const add = (Kind, arr, material) => { if (arr.length) g.add(new Kind(geometry(arr), material)); };
    add(THREE.Mesh, s.positions, M.surface);
    add(THREE.LineSegments, s.featureLines, M.feature);
    add(THREE.LineSegments, s.sharpLines, M.sharp);
    add(THREE.Points, s.sharpPoints, M.sharpPoints);
    if (s.bad) {
      add(THREE.Mesh, s.bad.positions, M.bad);
      add(THREE.LineSegments, s.bad.edge, M.badEdge);
      add(THREE.Points, s.bad.points, M.badPoints);
    }
    this.render();
  }

  setSurfaceVisible(on) {
    this.groups.surface.visible = on;
    this.render();
  }

  /** Replaces the drawn tets with the buffers of one extract() (tetfaces.mjs). */
  showTets(x) {
    this.clear('mesh');
    const geom = new THREE.BufferGeometry();
    geom.setAttribute('position', new THREE.BufferAttribute(x.positions, 3));
    geom.setAttribute('tetCentroid', new THREE.BufferAttribute(x.centroids, 3));
    geom.setAttribute('color', new THREE.BufferAttribute(x.colours, 3, true));
    geom.setIndex(new THREE.BufferAttribute(x.index, 1));
    const nFaces = x.index.length / 3;
    geom.addGroup(0, 3 * x.opaqueFaces, 0);
    if (nFaces > x.opaqueFaces) geom.addGroup(3 * x.opaqueFaces, 3 * (nFaces - x.opaqueFaces), 1);
    geom.boundingSphere = new THREE.Sphere(new THREE.Vector3(), this.size * 2);
    const m = new THREE.Mesh(geom, [this.opaque, this.faded]);
    this.groups.mesh.add(m);
    if (x.edges && x.edges.length) {
      const eg = new THREE.BufferGeometry();
      eg.setAttribute('position', geom.getAttribute('position'));
      eg.setAttribute('tetCentroid', geom.getAttribute('tetCentroid'));
      eg.setIndex(new THREE.BufferAttribute(x.edges, 1));
      eg.boundingSphere = geom.boundingSphere;
      this.groups.mesh.add(new THREE.LineSegments(eg, this.edgeMaterial));
    }
    this.meshObject = m;
    this.faceTet = x.faceTet;
    this.render();
  }

  /**
   * Outlines the clipping plane inside the box (relative coordinates):
   * axis 0, 1 or 2, at `at` along it; null hides it.
   */
  showPlane(plane) {
    if (!this.planeLine) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(12), 3));
      this.planeLine = new THREE.LineLoop(g, new THREE.LineBasicMaterial({ color: 0x0b5cad, transparent: true, opacity: 0.7 }));
      this.scene.add(this.planeLine);
    }
    this.planeLine.visible = Boolean(plane);
    if (plane) {
      const { axis, at, lo, hi } = plane;
      const [u, v] = [0, 1, 2].filter((k) => k !== axis);
      const m = 0.04 * Math.max(...hi.map((x, k) => x - lo[k]));
      const p = this.planeLine.geometry.getAttribute('position');
      [[lo[u] - m, lo[v] - m], [hi[u] + m, lo[v] - m], [hi[u] + m, hi[v] + m], [lo[u] - m, hi[v] + m]].forEach(([a, b], i) => {
        const xyz = [0, 0, 0];
        xyz[axis] = at; xyz[u] = a; xyz[v] = b;
        p.setXYZ(i, ...xyz);
      });
      p.needsUpdate = true;
      this.planeLine.geometry.computeBoundingSphere();
    }
    this.render();
  }

  setShrink(s) {
    this.shrink.value = s;
    this.render();
  }

  /** The tet under a client point, or -1. */
  pick(clientX, clientY) {
    if (!this.meshObject) return -1;
    const r = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    let target = this.meshObject;
    const s = this.shrink.value;
    if (s < 1) {
      // The shader shrinks the tets: pick on the positions as drawn.
      const g = this.meshObject.geometry;
      const p = g.getAttribute('position').array, c = g.getAttribute('tetCentroid').array;
      const q = new Float32Array(p.length);
      for (let i = 0; i < p.length; ++i) q[i] = c[i] + (p[i] - c[i]) * s;
      const shrunk = new THREE.BufferGeometry();
      shrunk.setAttribute('position', new THREE.BufferAttribute(q, 3));
      shrunk.setIndex(g.index);
      target = new THREE.Mesh(shrunk, this.opaque);
    }
    const hit = ray.intersectObject(target, false).find((h) => h.face);
    if (target !== this.meshObject) target.geometry.dispose();
    return hit ? this.faceTet[hit.faceIndex] : -1;
  }

  /** Draws the picked tet's edges on top of everything. */
  mark(info) {
    this.clear('marker');
    if (!info) return;
    const c = info.corners;
    const e = [0, 1, 0, 2, 0, 3, 1, 2, 1, 3, 2, 3];
    const arr = new Float32Array(e.length * 3);
    e.forEach((v, i) => arr.set(c.subarray(3 * v, 3 * v + 3), 3 * i));
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(arr, 3));
    this.groups.marker.add(new THREE.LineSegments(g, this.mats.marker));
    this.render();
  }

  /** Moves the camera to look at a point from the current direction, at a distance for a feature of `size`. */
  lookAt(point, size) {
    const target = new THREE.Vector3(...point);
    const dir = this.camera.position.clone().sub(this.controls.target).normalize();
    const dist = Math.max(size * 12, this.size / 20);
    this.controls.target.copy(target);
    this.camera.position.copy(target.clone().add(dir.multiplyScalar(dist)));
    this.controls.update();
    this.render();
  }

  showOverlays({ balls, pumped }, origin) {
    this.clear('overlay');
    if (balls && balls.length) {
      const sphere = new THREE.SphereGeometry(1, 20, 14);
      const inst = new THREE.InstancedMesh(sphere, this.mats.balls, balls.length);
      const m = new THREE.Matrix4();
      balls.forEach((b, i) => {
        m.makeScale(b.radius, b.radius, b.radius);
        m.setPosition(b.center[0] - origin[0], b.center[1] - origin[1], b.center[2] - origin[2]);
        inst.setMatrixAt(i, m);
      });
      this.groups.overlay.add(inst);
    }
    if (pumped && pumped.length) {
      const pg = new THREE.BufferGeometry();
      pg.setAttribute('position', new THREE.BufferAttribute(pumped, 3));
      this.groups.overlay.add(new THREE.Points(pg, this.mats.pumped));
    }
    this.render();
  }
}
