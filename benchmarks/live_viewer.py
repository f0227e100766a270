"""The live iCub's speed in headless Chromium (`make bench` prints it; also
`python benchmarks/live_viewer.py`).

A page with the button and rod views (`icm.viewer.write_page`, in a temporary folder)
is opened from disk in Debian's Chromium at laptop width (1366 px), offline, as the
browser tests open it. Measured:

- click to first frame: from the click on "Start the live view" to the first frame
  drawn (loading the scripts, decoding and instantiating the wasm, compiling the
  model, building the scene), best of `repeats` fresh pages;
- frames per second while the iCub presses a button (the canvas at the page's column
  width), and simulated seconds per wall-clock second over that press (the view runs
  the physics at the reader's speed, 1x: this must not fall below 1);
- the physics alone, with no drawing (the viewer's own stepping of a press, and of the
  48 rod moves): how many times faster than real time it could run;
- the WebAssembly memory after starting, after 300 resets and after 15 restarts;
- what a reader downloads: the page's HTML per view, and on request, the viewer's
  scripts.
"""

import pathlib
import shutil
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]

FIRST_FRAME = """() => new Promise((resolve) => {
  const box = document.querySelectorAll(".icm-live")[0];
  const start = performance.now();
  box.addEventListener("icm-live-frame", () => resolve(performance.now() - start), {once: true});
  box.querySelector(".icm-live-start").click();
})"""

PRESS = """async () => {
  const live = icmLive.views[0];
  const frames = live.stats.frames, simulated = live.stats.simulated, wall = live.stats.wall;
  const start = performance.now();
  live.box.querySelector(".icm-live-controls button").click();
  await new Promise((resolve) => {
    const wait = () => (live.sim.busy ? setTimeout(wait, 20) : resolve());
    setTimeout(wait, 20);
  });
  const seconds = (performance.now() - start) / 1000;
  return {fps: (live.stats.frames - frames) / seconds,
          realtime: (live.stats.simulated - simulated) / (live.stats.wall - wall),
          canvas: [live.canvas.width, live.canvas.height]};
}"""

PHYSICS = """async () => {
  const engine = await icmLive.loadEngine("_static/");
  const data = document.querySelectorAll(".icm-live-data");
  const buttons = new icmLive.ButtonsSim(engine, JSON.parse(data[0].textContent));
  const rods = new icmLive.RodsSim(engine, JSON.parse(data[1].textContent));
  try {
    let simulated = 0, start = performance.now();
    for (let b = 0; b < 5; b++) {
      buttons.reset(buttons.lights);
      buttons.press(b);
      buttons.finish();
      simulated += buttons.data.time;
    }
    const pressRate = simulated / ((performance.now() - start) / 1000);
    simulated = 0;
    start = performance.now();
    for (const key of Object.keys(rods.spec.moves)) {
      const [c, r, a] = key.split(",").map(Number);
      rods.reset([c, r]);
      rods.move(a);
      rods.finish();
      simulated += rods.data.time;
    }
    return {press: pressRate, rods: simulated / ((performance.now() - start) / 1000)};
  } finally {
    buttons.dispose();
    rods.dispose();
  }
}"""

MEMORY = """async (resets) => {
  const live = icmLive.views[0];
  for (let i = 0; i < resets; i++) live.sim.reset(live.sim.lights);
  return icmLive.memory();
}"""


def measure(repeats=3):
    """The figures above, as a dict; None where Chromium or Playwright is missing."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    if chromium is None:
        return None
    from icm import viewer

    with tempfile.TemporaryDirectory() as folder:
        views = [viewer.live_scene("buttons", live=True), viewer.live_scene("rods", live=True)]
        page_path = viewer.write_page(folder, views, ROOT / "book" / "_static")
        static = pathlib.Path(folder) / "_static"
        on_request = sum((static / name).stat().st_size for name in viewer.STATIC_FILES
                         if name != "icm.css")
        out = {"html_per_view": [len(view.html) for view in views],
               "on_request_bytes": on_request, "first_frame_ms": []}
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=chromium, args=FLAGS)
            for attempt in range(repeats):
                context = browser.new_context(offline=True,
                                              viewport={"width": 1366, "height": 900})
                page = context.new_page()
                page.goto(page_path.as_uri(), wait_until="load")
                out["first_frame_ms"].append(page.evaluate(FIRST_FRAME))
                if attempt == repeats - 1:
                    out.update(page.evaluate(PRESS))
                    out["physics"] = page.evaluate(PHYSICS)
                    out["memory_start"] = page.evaluate(MEMORY, 0)
                    out["memory_resets"] = page.evaluate(MEMORY, 300)
                    for _ in range(15):
                        page.locator(".icm-live").nth(0).get_by_role(
                            "button", name="Close the live view").click()
                        page.evaluate(FIRST_FRAME)
                    out["memory_restarts"] = page.evaluate(MEMORY, 0)
                context.close()
            browser.close()
    return out


def report(figures):
    """The figures as lines of text."""
    if figures is None:
        return ["  skipped: Chromium (apt-get install chromium) or Playwright is missing"]
    mb = 1024 * 1024
    physics = figures["physics"]
    return [
        f"  click to first frame: {min(figures['first_frame_ms']):.0f} ms (best of "
        f"{len(figures['first_frame_ms'])}; all {', '.join(f'{t:.0f}' for t in figures['first_frame_ms'])})",
        f"  during a press, canvas {figures['canvas'][0]} x {figures['canvas'][1]} px at "
        f"1366 px page width: {figures['fps']:.1f} frames/s; simulated seconds per "
        f"second {figures['realtime']:.2f} ({'ok' if figures['realtime'] >= 0.99 else 'MISSED'}"
        ": at least real time)",
        f"  the physics alone: presses {physics['press']:.0f} x real time, rod moves "
        f"{physics['rods']:.0f} x real time",
        f"  WebAssembly memory: {figures['memory_start'] / mb:.1f} MB after starting, "
        f"{figures['memory_resets'] / mb:.1f} MB after 300 resets, "
        f"{figures['memory_restarts'] / mb:.1f} MB after 15 restarts",
        f"  downloads: {', '.join(f'{n / 1024:.0f} kB' for n in figures['html_per_view'])} "
        f"of HTML per view (the still and the data); {figures['on_request_bytes'] / mb:.2f} MB "
        "of scripts, only once a view is started",
    ]


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    print("The live iCub in headless Chromium:")
    print("\n".join(report(measure())))
