"""Re-vendors MuJoCo's WebAssembly build, three.js and axe-core from npm, from the pinned
lock file beside this script, into book/_static/vendor/mujoco, book/_static/vendor/three
and book/_static/vendor/axe.

    python book/_static/vendor/npm/revendor.py

Needs node and npm; nothing else is downloaded, and nothing here runs at build or read
time. Steps:

1. `npm ci` in a temporary copy of this folder (package.json and package-lock.json: the
   exact versions and checksums), so that no node_modules lands in the book's sources;
2. the packages' ES modules become classic scripts, which load from `file://` as well as
   over HTTP (browsers refuse ES modules and fetched WebAssembly from `file://`), with
   the esbuild of the lock file:
   - three.js: the classes `three-entry.js` lists, bundled and minified, as the global
     `THREE` (vendor/three/three.min.js);
   - @mujoco/mujoco: its single-threaded `mujoco.js`, minified, as the global
     `loadMujoco` (vendor/mujoco/mujoco.js; `import.meta.url` is only used to locate
     the wasm file, which the viewer never fetches: it hands the bytes over);
   - its `mujoco.wasm`, unchanged, gzipped and base64-encoded into a classic script
     that sets `window.icmMujocoWasm` (vendor/mujoco/mujoco-wasm.js); the viewer decodes
     it with the browser's DecompressionStream;
3. axe-core (the accessibility checker that tests/test_browser.py runs on every page of
   the built book; no page loads it): its `axe.min.js` as published, with its LICENSE
   and LICENSE-3RD-PARTY.txt (vendor/axe/);
4. the licences: three's LICENSE; @mujoco/mujoco ships none (its package.json says
   Apache-2.0), so MuJoCo's own LICENSE and LICENSES_THIRD_PARTY.md are copied from the
   `mujoco` Python package installed here (the same project and licence).

The output is deterministic (gzip without a time stamp), so a re-vendor of the same
lock file changes no byte.
"""

import base64
import gzip
import importlib.metadata
import json
import pathlib
import shutil
import subprocess
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
VENDOR = HERE.parent


def run(command, folder):
    print("+", " ".join(command))
    subprocess.run(command, cwd=folder, check=True)


def mujoco_licences():
    """MuJoCo's LICENSE and LICENSES_THIRD_PARTY.md, from the installed Python package."""
    files = importlib.metadata.distribution("mujoco").files
    found = {path.name: path.locate() for path in files
             if path.name in ("LICENSE", "LICENSES_THIRD_PARTY.md")}
    missing = {"LICENSE", "LICENSES_THIRD_PARTY.md"} - set(found)
    if missing:
        raise SystemExit(f"the mujoco Python package has no {', '.join(sorted(missing))}")
    return found


def main():
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        for name in ("package.json", "package-lock.json", "three-entry.js"):
            shutil.copy(HERE / name, work / name)
        run(["npm", "ci", "--no-audit", "--no-fund"], work)
        modules = work / "node_modules"
        esbuild = str(modules / ".bin" / "esbuild")
        three, mujoco = VENDOR / "three", VENDOR / "mujoco"
        three.mkdir(exist_ok=True)
        mujoco.mkdir(exist_ok=True)
        run([esbuild, "three-entry.js", "--bundle", "--minify", "--format=iife",
             "--global-name=THREE", "--legal-comments=eof",
             f"--outfile={three / 'three.min.js'}"], work)
        shutil.copy(modules / "three" / "LICENSE", three / "LICENSE")
        package = modules / "@mujoco" / "mujoco"
        run([esbuild, str(package / "mujoco.js"), "--minify", "--format=iife",
             "--global-name=loadMujoco", "--define:import.meta.url=\"mujoco.js\"",
             f"--outfile={mujoco / 'mujoco.js'}"], work)
        wasm = gzip.compress((package / "mujoco.wasm").read_bytes(), compresslevel=9,
                             mtime=0)
        version = json.loads((package / "package.json").read_text())["version"]
        (mujoco / "mujoco-wasm.js").write_text(
            f"/* @mujoco/mujoco {version}: mujoco.wasm (Apache-2.0, see LICENSE), gzipped "
            "and base64-encoded by revendor.py */\n"
            f"window.icmMujocoWasm = \"{base64.b64encode(wasm).decode()}\";\n")
        for name, path in mujoco_licences().items():
            shutil.copy(path, mujoco / name)
        axe = VENDOR / "axe"
        axe.mkdir(exist_ok=True)
        for name in ("axe.min.js", "LICENSE", "LICENSE-3RD-PARTY.txt"):
            shutil.copy(modules / "axe-core" / name, axe / name)
    for path in sorted(p for name in ("three", "mujoco", "axe")
                       for p in (VENDOR / name).iterdir()):
        print(f"{path.relative_to(VENDOR)}: {path.stat().st_size:,} bytes")


if __name__ == "__main__":
    main()
