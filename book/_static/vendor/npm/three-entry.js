// The parts of three.js the book's viewer (book/_static/icm-live.js) uses: revendor.py
// bundles them into vendor/three/three.min.js as the global THREE.
export {
  BoxGeometry, CapsuleGeometry, Color, CylinderGeometry, DataTexture, DirectionalLight,
  HemisphereLight, Mesh, MeshStandardMaterial, NearestFilter, PerspectiveCamera,
  PlaneGeometry, RepeatWrapping, Scene, SphereGeometry, SRGBColorSpace, Vector3,
  WebGLRenderer,
} from "three";
