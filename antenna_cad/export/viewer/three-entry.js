// The parts of three.js the report's 3-D view uses, bundled into three.min.js (see README.md).
export {
  AmbientLight, BackSide, Box3, DirectionalLight, FrontSide, Mesh, MeshBasicMaterial, PerspectiveCamera, Plane,
  Scene, Vector3, WebGLRenderer,
} from "three";
export { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
export { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
