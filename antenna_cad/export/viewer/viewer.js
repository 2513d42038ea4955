// The report's interactive 3-D view: the build's <name>.glb (embedded as base64), drawn with the
// vendored three.js bundle (global THREE3D). Orbit, zoom and pan with the mouse; parts shown or
// hidden by group; a section plane across x, y or z. Drawn on demand (no animation loop); the
// canvas keeps its drawing buffer so it prints and so tests can read its pixels.
(function () {
  "use strict";
  const T = window.THREE3D;
  const root = document.getElementById("v3d");
  const canvas = root.querySelector("canvas");
  const info = JSON.parse(document.getElementById("v3d-parts").textContent);  // {groups: [...], parts: {label: group}}
  const say = (text) => { root.querySelector(".v3d-msg").textContent = text; };

  let renderer;
  try {
    renderer = new T.WebGLRenderer({canvas, antialias: true, preserveDrawingBuffer: true});
  } catch (err) {
    say("This browser cannot draw WebGL; the static views below show the assembly.");
    return;
  }
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0xffffff, 1);
  const scene = new T.Scene();
  const camera = new T.PerspectiveCamera(35, 1, 0.001, 1000);
  scene.add(new T.AmbientLight(0xffffff, 1.2));
  const lamp = new T.DirectionalLight(0xffffff, 2.2);
  camera.add(lamp);
  lamp.position.set(0.4, 0.8, 0.3);
  scene.add(camera);
  const controls = new T.OrbitControls(camera, canvas);
  const plane = new T.Plane(new T.Vector3(0, 0, -1), 0);
  const byGroup = {};
  let box = null;

  function draw() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio())) renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    renderer.render(scene, camera);
  }

  function frame() {  // an isometric view from the feed side (DESIGN.md frame: +Y up, +Z the beam)
    const size = box.getSize(new T.Vector3()).length(), centre = box.getCenter(new T.Vector3());
    camera.near = size / 100;
    camera.far = size * 100;
    camera.position.copy(centre).add(new T.Vector3(1, 0.8, -1.4).normalize().multiplyScalar(1.7 * size));
    controls.target.copy(centre);
    controls.update();
    draw();
  }

  function setGroup(group, visible) {
    (byGroup[group] || []).forEach((o) => { o.visible = visible; });
    draw();
  }

  function section() {  // the plane keeps the half below the slider's position along the chosen axis
    const axis = root.querySelector(".v3d-axis").value;
    const flip = root.querySelector(".v3d-flip").checked;
    const t = Number(root.querySelector(".v3d-cut").value) / 1000;
    if (!axis) {
      renderer.clippingPlanes = [];
    } else {
      const k = "xyz".indexOf(axis), n = new T.Vector3();
      n.setComponent(k, flip ? 1 : -1);
      const at = box.min.getComponent(k) + t * (box.max.getComponent(k) - box.min.getComponent(k));
      plane.set(n, flip ? -at : at);
      renderer.clippingPlanes = [plane];
      root.querySelector(".v3d-cut-mm").textContent = `${axis} = ${(at * 1000).toFixed(1)} mm`;
    }
    root.querySelector(".v3d-cut-mm").hidden = !axis;
    draw();
  }

  function controlsFor(groups) {
    const list = root.querySelector(".v3d-groups");
    groups.forEach((g) => {
      const label = document.createElement("label");
      const box = document.createElement("input");
      box.type = "checkbox";
      box.checked = g.shown;
      box.dataset.group = g.name;
      box.addEventListener("change", () => setGroup(g.name, box.checked));
      label.append(box);
      g.colours.forEach((c) => {
        const s = document.createElement("span");
        s.className = "swatch";
        s.style.background = c;
        label.append(s);
      });
      label.append(` ${g.name} (${g.count})`);
      list.append(label);
    });
    ["change", "input"].forEach((e) => {
      root.querySelector(".v3d-axis").addEventListener(e, section);
      root.querySelector(".v3d-cut").addEventListener(e, section);
      root.querySelector(".v3d-flip").addEventListener(e, section);
    });
    root.querySelector(".v3d-reset").addEventListener("click", frame);
  }

  const b64 = document.getElementById("v3d-glb").textContent.trim();
  const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
  new T.GLTFLoader().parse(bytes.buffer, "", (gltf) => {
    const model = gltf.scene;
    const meshes = [];
    model.traverse((o) => { if (o.isMesh) meshes.push(o); });
    meshes.forEach((o) => {
      // a cut solid shows its inside faces flat in a darker tone of its colour: they read as the section
      o.material.side = T.FrontSide;
      const inside = new T.MeshBasicMaterial({color: o.material.color.clone().multiplyScalar(0.72), side: T.BackSide});
      o.add(new T.Mesh(o.geometry, inside));
      const label = o.name in info.parts ? o.name : o.parent.name;
      const group = info.parts[label];
      (byGroup[group] = byGroup[group] || []).push(o);
    });
    scene.add(model);
    box = new T.Box3().setFromObject(model);
    info.groups.forEach((g) => { if (!g.shown) (byGroup[g.name] || []).forEach((o) => { o.visible = false; }); });
    controlsFor(info.groups);
    controls.addEventListener("change", draw);
    window.addEventListener("resize", draw);
    window.addEventListener("beforeprint", draw);
    frame();
    root.dataset.ready = "1";
    window.antennaView = {draw, setGroup, section, groups: Object.keys(byGroup)};
  }, (err) => say(`The 3-D model could not be read: ${err.message || err}`));
})();
