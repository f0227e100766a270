/* The live iCub of the book: the one viewer every page shares (icm/viewer.py makes the
   views; see its docstring).

   MuJoCo's WebAssembly build steps the package's own MJCF and three.js draws it. What is
   hard was computed in Python and arrives with the view: the arm's postures (inverse
   kinematics) as motion segments, and the learners' runs. Here the segments are stepped
   as icub.Arm.move steps them, with the rules of the Python tasks:
   - ButtonsSim: ButtonsTask.update and PhysicsButtonConsole.press
     (icm/envs/buttons/physics.py);
   - RodsSim: PhysicsRodTable.move (icm/envs/rods/physics.py).
   Every WebAssembly object made here is freed with .delete(). Only classic scripts are
   loaded, and the wasm bytes come inside one: that works from file:// as over HTTP. */
(function () {
  "use strict";
  if (window.icmLive) return;

  const VENDOR = ["vendor/three/three.min.js", "vendor/mujoco/mujoco.js",
                  "vendor/mujoco/mujoco-wasm.js"];
  const MAX_FRAME_SECONDS = 1.0;  // simulated seconds a frame may run, at most
  const SPEEDS = [1, 2, 4];

  /* ------------------------------------------------------------------ loading */

  function loadScript(url) {
    return new Promise((resolve, reject) => {
      const script = document.createElement("script");
      script.src = url;
      script.onload = resolve;
      script.onerror = () => reject(new Error("could not load " + url));
      document.head.appendChild(script);
    });
  }

  function decodeBase64(text) {
    if (Uint8Array.fromBase64) return Uint8Array.fromBase64(text);
    const bytes = atob(text), out = new Uint8Array(bytes.length);
    for (let i = 0; i < bytes.length; i++) out[i] = bytes.charCodeAt(i);
    return out;
  }

  async function gunzip(bytes) {
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
    return new Response(stream).arrayBuffer();
  }

  let engine = null;  // {mujoco, memory}, once per page

  function loadEngine(base) {
    if (!engine) {
      engine = (async () => {
        for (const file of VENDOR) await loadScript(base + file);
        const wasm = await gunzip(decodeBase64(window.icmMujocoWasm));
        window.icmMujocoWasm = undefined;  // 3 MB of text, no longer needed
        let memory = null, failed;
        const failure = new Promise((resolve, reject) => { failed = reject; });
        const mujoco = await Promise.race([failure, window.loadMujoco.default({
          locateFile: (name) => name,  // never fetched: the bytes are handed over here
          instantiateWasm(imports, receive) {
            WebAssembly.instantiate(wasm, imports).then((result) => {
              memory = result.instance.exports.memory;
              receive(result.instance, result.module);
            }, failed);
            return {};
          },
        })]);
        return {mujoco, memory};
      })();
      engine.catch(() => { engine = null; });  // a later start may try again
    }
    return engine;
  }

  // What the browser lacks for the live view ({missing}), or whether it draws WebGL in
  // software ({software}: then without antialiasing and shadows, twice the frames).
  function probe() {
    if (typeof WebAssembly !== "object") return {missing: "no WebAssembly"};
    if (typeof DecompressionStream !== "function") return {missing: "no DecompressionStream"};
    const gl = document.createElement("canvas").getContext("webgl2");
    if (!gl) return {missing: "no WebGL 2"};
    const info = gl.getExtension("WEBGL_debug_renderer_info");
    const renderer = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : "";
    const lose = gl.getExtension("WEBGL_lose_context");
    if (lose) lose.loseContext();
    return {missing: null, software: /swiftshader|llvmpipe|software/i.test(renderer)};
  }

  /* ------------------------------------------------------------------ physics */

  // icub.minimum_jerk, in the same floating-point operations.
  const minimumJerk = (s) => s * s * s * (10.0 + s * (-15.0 + 6.0 * s));

  // A scene and the program of motion segments the arm is running. A program is a list
  // of functions, called in turn when the previous segment ends; each returns a segment
  // [joint targets or null (hold), updates, stop condition (optional)] or null (done at
  // once). update() runs one 20 ms control update, as one row of icub.Arm.move.
  class Sim {
    constructor(engine, spec) {
      this.mj = engine.mujoco;
      this.spec = spec;
      this.model = this.mj.MjModel.from_xml_string(spec.xml);
      try {
        this.data = new this.mj.MjData(this.model);
      } catch (error) {
        this.model.delete();
        throw error;
      }
      const joints = spec.arm.joints;
      this.armQpos = joints.map((name) => this.qposOf(name));
      this.armDofs = joints.map((name) => this.model.jnt_dofadr[this.id("JOINT", name)]);
      this.armCtrl = joints.map((name) => this.id("ACTUATOR", name));
      this.program = [];
      this.segment = null;
      this.carry = 0;
      this.recorder = null;  // called after every update (the tests record with it)
      this.last = null;      // what the last action did
    }

    id(kind, name) {
      const id = this.mj.mj_name2id(this.model, this.mj.mjtObj["mjOBJ_" + kind].value, name);
      if (id < 0) throw new Error(`the scene has no ${kind.toLowerCase()} ${name}`);
      return id;
    }

    qposOf(joint) { return this.model.jnt_qposadr[this.id("JOINT", joint)]; }

    dispose() {
      if (this.data) this.data.delete();
      if (this.model) this.model.delete();
      this.data = this.model = null;
    }

    // icub.Arm.place: the arm at rest at q, its actuators holding it.
    place(q) {
      const qpos = this.data.qpos, qvel = this.data.qvel, ctrl = this.data.ctrl;
      this.armQpos.forEach((a, j) => { qpos[a] = q[j]; });
      this.armDofs.forEach((d) => { qvel[d] = 0; });
      this.armCtrl.forEach((c, j) => { ctrl[c] = q[j]; });
    }

    armTargets() {
      const ctrl = this.data.ctrl;
      return this.armCtrl.map((c) => ctrl[c]);
    }

    clip(q) {
      const {lower, upper} = this.spec.arm;
      return q.map((v, j) => Math.min(Math.max(v, lower[j]), upper[j]));
    }

    // Drops the rest of the program (the state stays as it is).
    stop() {
      this.program = [];
      this.segment = null;
      this.carry = 0;
    }

    restart() {
      this.stop();
      this.last = null;
      this.mj.mj_resetData(this.model, this.data);
    }

    get busy() { return this.segment !== null || this.program.length > 0; }

    update() {
      while (this.segment === null) {
        if (this.program.length === 0) return false;
        const next = this.program.shift()();
        if (next) {
          const start = this.armTargets();
          this.segment = {start, goal: this.clip(next[0] || start), n: next[1],
                          stop: next[2] || null, k: 0};
        }
      }
      const s = this.segment, ctrl = this.data.ctrl;
      s.k += 1;
      const p = minimumJerk(s.k / s.n);
      this.armCtrl.forEach((c, j) => { ctrl[c] = s.start[j] + p * (s.goal[j] - s.start[j]); });
      for (let i = 0; i < this.spec.arm.substeps; i++) this.mj.mj_step(this.model, this.data);
      this.watch();
      if (this.recorder) this.recorder(this);
      if (s.k >= s.n || (s.stop && s.stop())) this.segment = null;
      return true;
    }

    watch() {}

    // Runs whole updates for `seconds` of simulated time (carrying the rest over).
    advance(seconds) {
      const dt = this.spec.arm.update_seconds;
      this.carry = Math.min(this.carry + seconds, MAX_FRAME_SECONDS);
      while (this.carry >= dt && this.update()) this.carry -= dt;
      if (!this.busy) this.carry = 0;
    }

    // Runs the program to its end; returns what the last action did.
    finish() {
      while (this.update());
      return this.last;
    }

    queueSegments(segments) {
      this.program.push(...segments.map((segment) => () => segment));
    }
  }

  class ButtonsSim extends Sim {
    constructor(engine, spec) {
      super(engine, spec);
      const rules = spec.rules;
      this.buttonQpos = rules.buttons.map((name) => this.qposOf(name));
      this.caps = rules.caps.map((name) => this.id("GEOM", name));
      this.lightMaterials = rules.light_materials.map((name) => this.id("MATERIAL", name));
      this.lidQpos = rules.lids.map((name) => this.qposOf(name));
      this.lidCtrl = rules.lids.map((name) => this.id("ACTUATOR", name));
      this.reset(ButtonsSim.layout(rules, rules.green_candidates[0]));
    }

    static layout(rules, green) {
      return rules.buttons.map((_, b) => (b === rules.red_button ? 1 : b === green ? 2 : 0));
    }

    // A new trial (ButtonsTask.initialize_episode): lights, buttons up, lids shut, arm home.
    reset(lights) {
      this.restart();
      this.lights = lights.slice();
      const matid = this.model.geom_matid, qpos = this.data.qpos;
      this.caps.forEach((geom, b) => { matid[geom] = this.lightMaterials[lights[b]]; });
      this.buttonQpos.forEach((a) => { qpos[a] = 0; });
      this.lidQpos.forEach((a) => { qpos[a] = 0; });
      this.setLidTargets([0, 0]);
      this.place(this.spec.home);
      this.down = lights.map(() => false);
      this.openedAt = [null, null];
      this.clearLog();
      this.mj.mj_forward(this.model, this.data);
    }

    clearLog() {
      this.log = [];
      this.deepest = this.lights.map(() => 0);
    }

    setLidTargets(targets) {
      const ctrl = this.data.ctrl;
      this.lidCtrl.forEach((c, i) => { ctrl[c] = targets[i]; });
    }

    lidAngle(i) { return this.data.qpos[this.lidQpos[i]]; }

    depths() {
      const qpos = this.data.qpos;
      return this.buttonQpos.map((a) => -qpos[a]);
    }

    boxes() {
      return [0, 1].map((i) => (this.lidAngle(i) >= this.spec.rules.box_open_angle ? 1 : 0));
    }

    // ButtonsTask.update: new presses open the lid of their light's colour for a while.
    watch() {
      const rules = this.spec.rules, now = this.data.time, depths = this.depths();
      depths.forEach((d, b) => { this.deepest[b] = Math.max(this.deepest[b], d); });
      if (Math.max(...depths) > rules.press_depth || this.down.some(Boolean)) {
        depths.forEach((d, b) => {
          if (d > rules.press_depth && !this.down[b]) {
            this.log.push(b);
            const light = this.lights[b];
            if (light !== 0) this.openedAt[light === 1 ? 0 : 1] = now;
            this.down[b] = true;
          }
        });
        this.down = this.down.map((down, b) => down && depths[b] >= rules.press_depth / 2);
      }
      this.setLidTargets(this.openedAt.map((at) => (
        at !== null && now - at < rules.lid_open_time ? rules.lid_open_angle : 0)));
    }

    // PhysicsButtonConsole.press: shut the lids (wait until they are), run the motion,
    // then wait for a lid it opened to open. `segments`: the scripted press by default.
    press(button, segments) {
      const rules = this.spec.rules, shut = rules.lid_shut_angle;
      const bothShut = () => this.lidAngle(0) < shut && this.lidAngle(1) < shut;
      let before;
      this.program.push(() => {
        this.openedAt = [null, null];
        this.setLidTargets([0, 0]);
        return bothShut() ? null : [null, rules.lid_wait_updates, bothShut];
      }, () => {
        this.clearLog();
        before = this.openedAt.slice();
        return null;
      });
      this.queueSegments(segments || this.spec.presses[button]);
      this.program.push(() => {
        const waiting = [0, 1].filter((i) => before[i] === null && this.openedAt[i] !== null);
        const open = () => waiting.every((i) => this.lidAngle(i) >= rules.box_open_angle);
        return open() ? null : [null, rules.lid_wait_updates, open];
      }, () => {
        this.last = {button, boxes: this.boxes(), log: this.log.slice(),
                     deepest: this.deepest.slice()};
        return null;
      });
    }
  }

  class RodsSim extends Sim {
    constructor(engine, spec) {
      super(engine, spec);
      const rules = spec.rules;
      this.rodBodies = rules.bodies.map((name) => this.id("BODY", name));
      this.rodDofs = rules.bodies.map((name) => this.model.jnt_dofadr[this.id("JOINT", name)]);
      this.fingertip = this.id("SITE", "fingertip");
      this.cells = [];
      for (let r = 0; r < rules.rows; r++) {
        for (let c = 0; c < rules.columns; c++) {
          this.cells.push({cell: [c, r], geom: this.id("GEOM", `cell_${c}_${r}`)});
        }
      }
      this.reset(rules.start_cell);
    }

    // A new episode (RodsTask.initialize_episode): rods upright, the hand over `cell`.
    reset(cell) {
      this.restart();
      this.place(this.spec.cells[cell.join(",")]);
      this.cell = cell.slice();
      this.mj.mj_forward(this.model, this.data);
    }

    tilts() {
      const xmat = this.data.xmat;
      return this.rodBodies.map((b) => Math.acos(Math.min(Math.max(xmat[9 * b + 8], -1), 1)));
    }

    toppled() {
      return this.tilts().map((tilt) => (tilt > this.spec.rules.topple_tilt ? 1 : 0));
    }

    rodSpeed() {
      const qvel = this.data.qvel;
      let fastest = 0;
      for (const dof of this.rodDofs) {
        for (let i = 0; i < 6; i++) fastest = Math.max(fastest, Math.abs(qvel[dof + i]));
      }
      return fastest;
    }

    // RodsPhysics.hand_cell: the cell whose centre is nearest the fingertip.
    handCell() {
      const xpos = this.data.geom_xpos, tip = this.data.site_xpos, f = 3 * this.fingertip;
      let best = null, nearest = Infinity;
      for (const {cell, geom} of this.cells) {
        const d = Math.hypot(xpos[3 * geom] - tip[f], xpos[3 * geom + 1] - tip[f + 1]);
        if (d < nearest) { nearest = d; best = cell; }
      }
      return best;
    }

    // PhysicsRodTable.move: along the grid line via the midpoint, settle, and if a rod
    // is tipping, let it fall and come to rest.
    move(action) {
      const rules = this.spec.rules, move = this.spec.moves[`${this.cell.join(",")},${action}`];
      const from = this.cell.slice();
      this.cell = move.to.slice();
      this.queueSegments(move.segments);
      this.program.push(() => (
        this.tilts().some((tilt) => tilt > rules.tipping_tilt)
          ? [null, rules.fall_updates, () => this.rodSpeed() < rules.rest_speed] : null
      ), () => {
        this.last = {from, action, rods: this.toppled(), hand: this.handCell()};
        return null;
      });
    }
  }

  /* ------------------------------------------------------------------ drawing */

  // The scene's geoms as three.js meshes, posed from MjData at every frame; a camera
  // that orbits (drag, or keys A/D/W/S) and zooms (wheel once focused, or +/-).
  class View {
    constructor(canvas, sim, software) {
      const T = window.THREE, model = sim.model, data = sim.data;
      this.sim = sim;
      this.canvas = canvas;
      this.renderer = new T.WebGLRenderer({canvas, antialias: !software});
      this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
      this.renderer.shadowMap.enabled = !software;
      this.scene = new T.Scene();
      this.scene.background = new T.Color().setRGB(0.78, 0.84, 0.9, T.SRGBColorSpace);
      this.scene.add(new T.HemisphereLight(0xffffff, 0x8a8070, 1.6));
      const key = new T.DirectionalLight(0xffffff, 2.2);
      key.position.set(0.6, -0.8, 2.2);
      key.target.position.set(0.3, -0.4, 0.4);
      key.castShadow = true;
      key.shadow.mapSize.set(1024, 1024);
      key.shadow.bias = -0.0005;  // no stripes on the thin grid markers
      key.shadow.normalBias = 0.01;
      Object.assign(key.shadow.camera, {left: -1, right: 1, top: 1, bottom: -1, far: 5});
      key.shadow.camera.updateProjectionMatrix();
      this.scene.add(key, key.target);
      this.camera = new T.PerspectiveCamera(45, 4 / 3, 0.01, 30);
      this.camera.up.set(0, 0, 1);
      this.owned = [];  // geometries, materials and textures, disposed with the view
      this.meshes = [];
      const type = model.geom_type, size = model.geom_size, group = model.geom_group;
      for (let i = 0; i < model.ngeom; i++) {
        const geometry = this.geometry(type[i], size.subarray(3 * i, 3 * i + 3));
        if (!geometry || group[i] >= 3 || this.rgba(i)[3] === 0) continue;
        const mesh = new T.Mesh(geometry, new T.MeshStandardMaterial({roughness: 0.75}));
        this.owned.push(geometry, mesh.material);
        if (type[i] === 0) mesh.material.map = this.checker(size);
        mesh.matrixAutoUpdate = false;
        mesh.castShadow = type[i] !== 0 && this.rgba(i)[3] === 1;
        mesh.receiveShadow = true;
        mesh.userData = {geom: i, matid: null};
        this.meshes.push(mesh);
        this.scene.add(mesh);
      }
      // The view starts where one of the scene's cameras is, turned to the body it
      // targets; the view's data may set another distance, azimuth or elevation.
      const start = sim.spec.view, camera = sim.id("CAMERA", start.camera), eye = 3 * camera;
      const targetBody = model.cam_targetbodyid[camera];
      const look = 3 * (targetBody >= 0 ? targetBody : sim.id("BODY", "look_at"));
      const xpos = data.xpos, cam = data.cam_xpos;
      this.target = new T.Vector3(xpos[look], xpos[look + 1], xpos[look + 2]);
      const d = new T.Vector3(cam[eye], cam[eye + 1], cam[eye + 2]).sub(this.target);
      this.orbit = Object.assign({distance: d.length(), azimuth: Math.atan2(d.y, d.x),
                                  elevation: Math.asin(d.z / d.length())}, start.orbit);
      this.listen();
      this.applyOrbit();
    }

    // The colour MuJoCo draws geom i in: its material's, else its own.
    rgba(i) {
      const model = this.sim.model, matid = model.geom_matid[i];
      if (matid >= 0) return model.mat_rgba.subarray(4 * matid, 4 * matid + 4);
      return model.geom_rgba.subarray(4 * i, 4 * i + 4);
    }

    // A grey checker of 0.5 m squares, as MuJoCo draws the scenes' floor.
    checker(size) {
      const T = window.THREE;
      const texture = new T.DataTexture(new Uint8Array([133, 135, 140, 255, 117, 120, 125, 255,
                                                        117, 120, 125, 255, 133, 135, 140, 255]), 2, 2);
      texture.colorSpace = T.SRGBColorSpace;
      texture.magFilter = T.NearestFilter;
      texture.wrapS = texture.wrapT = T.RepeatWrapping;
      texture.repeat.set(size[0], size[1]);
      texture.needsUpdate = true;
      this.owned.push(texture);
      return texture;
    }

    geometry(type, size) {
      const T = window.THREE;
      switch (type) {
        case 0: return new T.PlaneGeometry(2 * size[0], 2 * size[1]);
        case 2: return new T.SphereGeometry(size[0], 24, 16);
        case 3: return new T.CapsuleGeometry(size[0], 2 * size[1], 8, 16).rotateX(Math.PI / 2);
        case 4: return new T.SphereGeometry(1, 24, 16).scale(size[0], size[1], size[2]);
        case 5: return new T.CylinderGeometry(size[0], size[0], 2 * size[1], 32).rotateX(Math.PI / 2);
        case 6: return new T.BoxGeometry(2 * size[0], 2 * size[1], 2 * size[2]);
        default: return null;  // height fields and meshes: the scenes have none
      }
    }

    listen() {
      const canvas = this.canvas;
      let drag = null;
      canvas.addEventListener("pointerdown", (event) => {
        canvas.focus();
        drag = {x: event.clientX, y: event.clientY};
        canvas.setPointerCapture(event.pointerId);
      });
      canvas.addEventListener("pointermove", (event) => {
        if (!drag) return;
        this.turn(-(event.clientX - drag.x) * 0.008, (event.clientY - drag.y) * 0.008);
        drag = {x: event.clientX, y: event.clientY};
      });
      canvas.addEventListener("pointerup", () => { drag = null; });
      canvas.addEventListener("wheel", (event) => {
        if (document.activeElement !== canvas) return;  // the page scrolls until focused
        event.preventDefault();
        this.zoom(Math.exp(event.deltaY * 0.001));
      }, {passive: false});
    }

    turn(azimuth, elevation) {
      this.orbit.azimuth += azimuth;
      this.orbit.elevation = Math.min(Math.max(this.orbit.elevation + elevation, -0.1), 1.5);
      this.applyOrbit();
    }

    zoom(factor) {
      this.orbit.distance = Math.min(Math.max(this.orbit.distance * factor, 0.25), 5);
      this.applyOrbit();
    }

    applyOrbit() {
      const {distance, azimuth, elevation} = this.orbit, t = this.target;
      this.camera.position.set(t.x + distance * Math.cos(elevation) * Math.cos(azimuth),
                               t.y + distance * Math.cos(elevation) * Math.sin(azimuth),
                               t.z + distance * Math.sin(elevation));
      this.camera.lookAt(t);
      this.dirty = true;
    }

    resize(width) {
      const height = Math.round(Math.min(width * 0.62, 560));
      this.renderer.setSize(width, height);
      this.camera.aspect = width / height;
      this.camera.updateProjectionMatrix();
      this.dirty = true;
    }

    draw() {
      const T = window.THREE, data = this.sim.data, model = this.sim.model;
      const xpos = data.geom_xpos, xmat = data.geom_xmat, matid = model.geom_matid;
      for (const mesh of this.meshes) {
        const i = mesh.userData.geom, p = 3 * i, r = 9 * i;
        mesh.matrix.set(xmat[r], xmat[r + 1], xmat[r + 2], xpos[p],
                        xmat[r + 3], xmat[r + 4], xmat[r + 5], xpos[p + 1],
                        xmat[r + 6], xmat[r + 7], xmat[r + 8], xpos[p + 2], 0, 0, 0, 1);
        mesh.matrixWorldNeedsUpdate = true;
        if (mesh.userData.matid !== matid[i]) {  // the lights change the caps' materials
          const [red, green, blue, alpha] = this.rgba(i);
          mesh.material.color.setRGB(red, green, blue, T.SRGBColorSpace);
          mesh.material.transparent = alpha < 1;
          mesh.material.opacity = alpha;
          mesh.userData.matid = matid[i];
        }
      }
      this.renderer.render(this.scene, this.camera);
      this.dirty = false;
    }

    dispose() {
      for (const thing of this.owned) thing.dispose();
      this.renderer.dispose();
      this.renderer.forceContextLoss();
    }
  }

  /* ------------------------------------------------------------------ the page */

  function element(tag, attributes, ...children) {
    const node = document.createElement(tag);
    for (const [name, value] of Object.entries(attributes || {})) {
      if (name.startsWith("on")) node.addEventListener(name.slice(2), value);
      else node.setAttribute(name, value);
    }
    node.append(...children);
    return node;
  }

  const LIGHT_WORDS = ["off", "red", "green"];
  const boxWords = (boxes) => (
    boxes[0] && boxes[1] ? "both boxes" : boxes[0] ? "the red box" : boxes[1] ? "the green box"
      : "nothing");

  // One live view: the stage (canvas and the replay's panel), its controls, its loop.
  class Live {
    constructor(box, engine, spec, software) {
      this.box = box;
      this.spec = spec;
      this.speed = 1;
      this.sim = new (spec.scene === "buttons" ? ButtonsSim : RodsSim)(engine, spec);
      try {
        const title = box.getAttribute("data-title") || "the simulated iCub";
        this.canvas = element("canvas", {
          tabindex: "0", role: "application",
          "aria-label": `Live 3D view of ${title}`, "aria-describedby": box.id + "-note"});
        this.panel = element("div", {class: "icm-live-panel"});
        this.status = element("p", {class: "icm-live-status", "aria-live": "polite"});
        this.controls = element("div", {class: "icm-live-controls"});
        this.log = element("ol", {class: "icm-live-log"});
        this.ui = element("div", {class: "icm-live-ui"}, this.status, this.controls, this.log);
        this.stage = box.querySelector(".icm-live-stage");
        this.stage.append(this.canvas, this.panel);
        box.querySelector(".icm-live-start").after(this.ui);
        this.view = new View(this.canvas, this.sim, software);
      } catch (error) {
        this.sim.dispose();
        throw error;
      }
      box.classList.add("icm-live-running");
      this.note = box.querySelector(".icm-live-note");
      this.stillNote = this.note.textContent;
      this.canvas.addEventListener("keydown", (event) => this.key(event));
      this.resizer = new ResizeObserver(() => this.view.resize(this.stage.clientWidth));
      this.resizer.observe(this.stage);
      this.view.resize(this.stage.clientWidth);
      this.stats = {frames: 0, firstFrame: null, wall: 0, simulated: 0};
      this.mode = MODES[spec.mode](this);
      this.note.textContent = "Live: MuJoCo is running in your browser. Drag the view to " +
        "turn it; click it, then use the wheel or + and - to zoom, A, D, W and S to turn" +
        (this.mode.keys ? `, ${this.mode.keys}.` : ".");
      this.waitUntil = 0;
      this.previous = performance.now();
      this.frame = requestAnimationFrame((now) => this.tick(now));
    }

    tick(now) {
      const wall = (now - this.previous) / 1000;
      this.previous = now;
      if (this.mode.next && !this.sim.busy && now >= this.waitUntil) this.mode.next();
      if (this.sim.busy) {
        const before = this.sim.data.time;
        this.sim.advance(wall * this.speed);
        this.view.dirty = true;
        if (this.sim.busy) {  // the pace of the physics, over frames it ran throughout
          this.stats.simulated += this.sim.data.time - before;
          this.stats.wall += wall;
        } else {
          this.mode.done();
        }
      }
      if (this.view.dirty) {
        this.view.draw();
        this.stats.frames += 1;
        if (this.stats.firstFrame === null) {
          this.stats.firstFrame = now;
          this.box.dispatchEvent(new CustomEvent("icm-live-frame"));
        }
      }
      this.frame = requestAnimationFrame((time) => this.tick(time));
    }

    pause(seconds) { this.waitUntil = performance.now() + 1000 * seconds / this.speed; }

    key(event) {
      const turns = {a: [0.1, 0], d: [-0.1, 0], w: [0, 0.08], s: [0, -0.08]};
      if (turns[event.key]) this.view.turn(...turns[event.key]);
      else if (event.key === "+" || event.key === "=") this.view.zoom(0.9);
      else if (event.key === "-") this.view.zoom(1 / 0.9);
      else if (!(this.mode.key && this.mode.key(event.key))) return;
      event.preventDefault();
    }

    button(label, onclick, attributes) {
      const node = element("button", Object.assign({type: "button", onclick}, attributes), label);
      this.controls.append(node);
      return node;
    }

    select(label, options, onchange) {
      const id = this.box.id + "-" + label.replace(/\W+/g, "-").toLowerCase();
      const node = element("select", {id, onchange: () => onchange(node.value)},
                           ...options.map(([value, text]) => element("option", {value}, text)));
      this.controls.append(element("label", {for: id}, label), node);
      return node;
    }

    close() {
      cancelAnimationFrame(this.frame);
      this.resizer.disconnect();
      this.view.dispose();
      this.sim.dispose();
      for (const node of [this.canvas, this.panel, this.ui]) node.remove();
      this.box.classList.remove("icm-live-running");
      this.note.textContent = this.stillNote;
      const start = this.box.querySelector(".icm-live-start");
      start.disabled = false;
      start.hidden = false;
      start.textContent = "Start the live view";
      views.splice(views.indexOf(this), 1);
    }
  }

  function speedControl(live) {
    live.select("Speed", SPEEDS.map((s) => [s, `${s}x`]), (value) => { live.speed = +value; });
  }

  function closeControl(live) {
    live.button("Close the live view", () => live.close());
  }

  // Pick a button; the iCub presses it. The green light can be moved; red stays.
  function buttonsMode(live) {
    const sim = live.sim, rules = live.spec.rules;
    const presses = rules.buttons.map((_, b) => live.button(`Press button ${b}`, () => press(b)));
    const say = (text) => {
      live.status.textContent = text + " Lights: " + sim.lights.map((light, b) => (
        light ? `button ${b} ${LIGHT_WORDS[light]}` : null)).filter(Boolean).join(", ") + ".";
    };
    const setBusy = (busy) => presses.forEach((node) => { node.disabled = busy; });
    const press = (b) => {
      if (sim.busy) return;
      setBusy(true);
      sim.press(b);
      say(`Pressing button ${b}...`);
    };
    let green = rules.green_candidates[0];
    live.select("Green light on", rules.green_candidates.map((b) => [b, `button ${b}`]), (b) => {
      green = +b;
      reset();
    });
    const reset = () => {
      sim.reset(ButtonsSim.layout(rules, green));
      setBusy(false);
      live.view.dirty = true;
      say("A new trial: the arm at home, both boxes shut.");
    };
    live.button("Reset", reset);
    closeControl(live);
    reset();
    return {
      keys: "the keys 0 to 4 to press a button",
      key: (key) => (/^[0-4]$/.test(key) ? (press(+key), true) : false),
      done: () => {
        const last = sim.last;
        setBusy(false);
        say(`Button ${last.button} went ${(1000 * last.deepest[last.button]).toFixed(1)} mm ` +
            `down and opened ${boxWords(last.boxes)}.`);
      },
    };
  }

  // Move the hand over the grid (arrow keys or buttons); the rods fall if physics says so.
  function rodsMode(live) {
    const sim = live.sim, rules = live.spec.rules;
    const labels = ["Forward (away from the robot)", "Backward (towards the robot)",
                    "Left (the robot's left)", "Right (the robot's right)"];
    const arrows = ["\u2191", "\u2193", "\u2190", "\u2192"];
    const moves = labels.map((label, a) => live.button(`${arrows[a]} ${label.split(" ")[0]}`,
                                                        () => move(a), {"aria-label": label}));
    const say = (text) => {
      const rods = sim.toppled().map((down, i) => `${rules.rods[i]} rod ${down ? "down" : "standing"}`);
      live.status.textContent = `${text} Hand over cell (${sim.cell.join(", ")}); ${rods.join(", ")}.`;
    };
    const move = (a) => {
      if (sim.busy) return;
      moves.forEach((node) => { node.disabled = true; });
      sim.move(a);
      say(`Moving ${rules.actions[a]}...`);
    };
    const reset = () => {
      sim.reset(rules.start_cell);
      moves.forEach((node) => { node.disabled = false; });
      live.view.dirty = true;
      say("Both rods stand again.");
    };
    live.button("Reset", reset);
    closeControl(live);
    reset();
    const keys = {ArrowUp: 0, ArrowDown: 1, ArrowLeft: 2, ArrowRight: 3};
    return {
      keys: "the arrow keys to move the hand",
      key: (key) => (key in keys ? (move(keys[key]), true) : false),
      done: () => {
        moves.forEach((node) => { node.disabled = false; });
        say(`Moved ${rules.actions[sim.last.action]}.`);
      },
    };
  }

  // A bar per quantity, for the replays' panels.
  function bars(entries, scale) {
    return element("div", {class: "icm-live-bars"}, ...entries.map(([label, value, colour]) => (
      element("div", {class: "icm-live-bar-row"}, element("span", {}, label),
              element("span", {class: "icm-live-bar",
                               style: `width: ${Math.min(100, 100 * value / scale).toFixed(1)}%;` +
                                      ` background: ${colour}`}),
              element("span", {}, value.toFixed(2))))));
  }

  // Replays a list of steps: each starts an action when the previous one is over.
  function replayControls(live, restart) {
    const play = live.button("Pause", () => {
      live.playing = !live.playing;
      play.textContent = live.playing ? "Pause" : "Play";
    });
    live.playing = true;
    speedControl(live);
    live.button("Restart", restart);
    closeControl(live);
  }

  // The goal-oriented learner's first trials: lights, presses, interest per task.
  function learnerMode(live) {
    const sim = live.sim, trials = live.spec.replay.trials, seed = live.spec.replay.seed;
    let t = 0, p = -1, agreed = 0, pressed = 0;
    const log = live.log;
    const restart = () => {
      sim.stop();
      t = 0; p = -1; agreed = 0; pressed = 0;
      log.replaceChildren();
      show("The run starts.");
    };
    const show = (line) => {
      const trial = trials[Math.min(t, trials.length - 1)];
      const interest = t > 0 ? trials[t - 1].interest : [0, 0];
      live.panel.replaceChildren(
        element("strong", {}, `Run 0 of seed ${seed}: trial ${Math.min(t + 1, trials.length)} ` +
                              `of ${trials.length}`),
        element("div", {}, "Lights: " + trial.lights.map((light, b) => (
          light ? `${LIGHT_WORDS[light]} on ${b}` : null)).filter(Boolean).join(", ")),
        element("div", {}, line),
        element("div", {}, "Interest after the last trial:"),
        bars([["red task", interest[0], "#c62828"], ["green task", interest[1], "#2e7d32"]], 1));
    };
    replayControls(live, restart);
    live.status.textContent = "The learner's presses, replayed in your browser's physics; " +
                              "each outcome is compared with the run's.";
    restart();
    return {
      next: () => {
        if (!live.playing || t >= trials.length) return;
        const trial = trials[t];
        if (p < 0) sim.reset(trial.lights);
        p += 1;
        sim.press(trial.presses[p]);
        show(`Press ${p + 1} of ${trial.presses.length}: button ${trial.presses[p]}...`);
      },
      done: () => {
        const trial = trials[t], expected = trial.boxes[p], got = sim.last.boxes;
        const same = got[0] === expected[0] && got[1] === expected[1];
        agreed += same;
        pressed += 1;
        const line = `Trial ${t + 1}, button ${trial.presses[p]}: opened ${boxWords(got)}` +
                     (same ? " (as in the run)" : ` (the run: ${boxWords(expected)})`);
        log.append(element("li", {}, line));
        if (p === trial.presses.length - 1) { t += 1; p = -1; live.pause(0.8); } else live.pause(0.3);
        show(line + `. ${agreed} of ${pressed} presses as in the run.`);
        live.replayAgreement = {agreed, pressed};
      },
    };
  }

  // The Q-learner's first episodes on the rods: moves, topples, prediction errors.
  function rodLearnerMode(live) {
    const sim = live.sim, replay = live.spec.replay, episodes = replay.episodes;
    const rules = live.spec.rules;
    let e = 0, m = -1, agreed = 0;
    const log = live.log;
    const restart = () => {
      sim.stop();
      e = 0; m = -1; agreed = 0;
      log.replaceChildren();
      show("The run starts.");
    };
    const show = (line) => {
      const episode = episodes[Math.min(e, episodes.length - 1)];
      live.panel.replaceChildren(
        element("strong", {}, `Run 0 of seed ${replay.seed}: episode ` +
                              `${Math.min(e + 1, episodes.length)} of ${episodes.length}`),
        element("div", {}, line),
        element("div", {}, "Prediction error in this episode (the robot's reward):"),
        bars([["red rod", episode.errors[0], "#c62828"], ["blue rod", episode.errors[1], "#1f5fcc"]], 1));
    };
    replayControls(live, restart);
    live.status.textContent = "The learner's moves, replayed in your browser's physics; " +
                              "each episode's ending is compared with the run's.";
    restart();
    return {
      next: () => {
        if (!live.playing || e >= episodes.length) return;
        const episode = episodes[e];
        if (m < 0) sim.reset(replay.start_cell);
        m += 1;
        sim.move(episode.actions[m]);
        show(`Move ${m + 1} of ${episode.actions.length}: ${rules.actions[episode.actions[m]]} ` +
             `from (${episode.cells[m].join(", ")})`);
      },
      done: () => {
        const episode = episodes[e], rods = sim.last.rods;
        const down = rods.indexOf(1) >= 0 ? rules.rods[rods.indexOf(1)] : null;
        if (down === null && m < episode.actions.length - 1) return;
        const same = down === episode.toppled && m === episode.actions.length - 1;
        agreed += same;
        const line = `Episode ${e + 1}: ${down ? `the ${down} rod fell` : "no rod fell"} after ` +
                     `${m + 1} moves` + (same ? " (as in the run)" : " (not as in the run)");
        log.append(element("li", {}, line));
        show(line);
        e += 1; m = -1;
        live.pause(0.8);
        live.replayAgreement = {agreed, episodes: e};
      },
    };
  }

  // The presses the robot formed: each button lit red, the robot's own movement for it.
  function formedMode(live) {
    const sim = live.sim, formed = live.spec.replay;
    const presses = formed.presses.map((_, b) => live.button(`Button ${b}'s formed press`, () => {
      if (sim.busy) return;
      presses.forEach((node) => { node.disabled = true; });
      sim.reset(formed.lights[b]);
      sim.press(b, formed.presses[b]);
      live.status.textContent = `Button ${b} lit red; the robot makes the movement it formed for it...`;
    }));
    closeControl(live);
    live.status.textContent = `The movements goal babbling (${formed.strategy.replace(/_/g, " ")}` +
                              `, run ${formed.run}) formed for each button. Pick one.`;
    return {
      done: () => {
        const last = sim.last, b = last.button;
        presses.forEach((node) => { node.disabled = false; });
        const down = last.log.length ? "pushed down button " + last.log.join(" and ") : "pushed no button down";
        live.status.textContent = `Button ${b}'s movement ${down} and opened ${boxWords(last.boxes)}. ` +
          `In Python it ${formed.pressed[b] ? "pressed" : "did not press"} button ${b} alone ` +
          "with the red box opening.";
      },
    };
  }

  const MODES = {
    scene: (live) => (live.spec.scene === "buttons" ? buttonsMode(live) : rodsMode(live)),
    learner: learnerMode,
    rod_learner: rodLearnerMode,
    formed: formedMode,
  };

  const views = [];

  function fallback(box, reason) {
    const start = box.querySelector(".icm-live-start");
    start.hidden = true;
    box.querySelector(".icm-live-note").textContent =
      `Your browser cannot run the live view (${reason}). The still above shows the scene, ` +
      "rendered from the same model when the book was built.";
  }

  async function start(box, base) {
    const {missing, software} = probe();
    if (missing) return fallback(box, missing);
    const button = box.querySelector(".icm-live-start");
    try {
      const spec = JSON.parse(box.querySelector(".icm-live-data").textContent);
      const live = new Live(box, await loadEngine(base), spec, software);
      views.push(live);
      button.hidden = true;
      return live;
    } catch (error) {
      console.error(error);
      fallback(box, "it failed to start: " + error.message);
      return null;
    }
  }

  window.icmLive = {
    start, loadEngine, ButtonsSim, RodsSim, views,
    memory: async () => (await engine).memory.buffer.byteLength,
  };
})();
