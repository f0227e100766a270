"""The book: notebooks committed clean, the table of contents complete, and a full
build with every notebook executed and every warning fatal."""

import nbformat
import pytest
import yaml

from conftest import ROOT, toc_files

NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebooks_are_committed_without_outputs(path):
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [], f"{path.name} has outputs: clear them before committing"
            assert cell.execution_count is None, f"{path.name} has execution counts"
    assert "widgets" not in notebook.metadata, f"{path.name} carries saved widget state"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebooks_set_mujoco_gl_only_if_unset_and_import_icm(path):
    # The first code cell after the one that installs icm on Binder or Colab (checked
    # by tests/test_launch.py).
    notebook = nbformat.read(path, as_version=4)
    first_code = [c for c in notebook.cells if c.cell_type == "code"][1].source
    assert 'os.environ.setdefault("MUJOCO_GL", "egl")' in first_code
    assert "import icm" in first_code
    assert "matplotlib.use(" not in "".join(c.source for c in notebook.cells)


def test_every_chapter_is_in_the_table_of_contents_and_exists():
    listed = set(toc_files())
    on_disk = {str(p.relative_to(ROOT).with_suffix(""))
               for p in (ROOT / "book").iterdir() if p.suffix in (".ipynb", ".md")}
    assert listed == on_disk


def test_build_configuration_makes_failures_fatal():
    config = yaml.safe_load((ROOT / "_config.yml").read_text())
    # Executed beforehand by execute_book.py (forced in the tests and CI), read from
    # the cache by the build; a notebook the build had to execute itself still fails
    # the build on an error, and within minutes if it hangs.
    assert config["execute"]["execute_notebooks"] == "cache"
    assert config["execute"]["raise_on_error"] is True
    assert config["execute"]["allow_errors"] is False
    assert config["execute"]["timeout"] <= 300


def _execute_book_module():
    import importlib.util

    spec = importlib.util.spec_from_file_location("execute_book",
                                                  ROOT / "book" / "_ext" / "execute_book.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_lost_wakeup_costs_a_second_not_the_whole_timeout():
    # The mechanism of the silent stall: a zmq.asyncio poll whose wakeup is lost (the
    # edge-triggered FD drained by someone reading zmq.EVENTS) waits for its whole
    # timeout, then finds the message and returns it as if nothing had happened.
    # jupyter_client's get_msg is such a poll; nbclient waits a cell's reply with one
    # get_msg of the whole cell timeout. execute_book.py cuts every wait in 1 s polls.
    import asyncio
    import time
    from queue import Empty

    import zmq
    import zmq.asyncio

    execute_book = _execute_book_module()

    async def reply_after_lost_wakeup(wrap, timeout):
        ctx = zmq.asyncio.Context()
        client = ctx.socket(zmq.DEALER)
        server = zmq.Context.instance().socket(zmq.ROUTER)
        port = server.bind_to_random_port("tcp://127.0.0.1")
        client.connect(f"tcp://127.0.0.1:{port}")
        await client.send(b"execute_request")
        identity, _ = server.recv_multipart()

        async def get_msg(timeout=None):  # as jupyter_client's AsyncZMQSocketChannel
            ready = await client.poll(None if timeout is None else int(timeout * 1000))
            if ready:
                return await client.recv()
            raise Empty

        waiting = asyncio.ensure_future(wrap(get_msg)(timeout=timeout))
        await asyncio.sleep(0.05)
        start = time.monotonic()
        server.send_multipart([identity, b"execute_reply"])
        time.sleep(0.05)  # the reply is in, the event loop has not run yet
        zmq.Socket.shadow(client.underlying).get(zmq.EVENTS)  # drains the wakeup
        reply = await waiting
        elapsed = time.monotonic() - start
        client.close(linger=0), server.close(linger=0), ctx.term()
        return reply, elapsed

    reply, elapsed = asyncio.run(reply_after_lost_wakeup(lambda f: f, 4.0))
    assert reply == b"execute_reply" and elapsed > 3.5  # silent: no error, just late
    reply, elapsed = asyncio.run(reply_after_lost_wakeup(execute_book.sliced, 60.0))
    assert reply == b"execute_reply" and elapsed < 1.5


def test_a_hanging_cell_fails_quickly_naming_the_notebook_and_the_cell(tmp_path):
    import subprocess
    import sys
    import time

    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nb.cells = [nbformat.v4.new_code_cell("x = 1"), nbformat.v4.new_markdown_cell("text"),
                nbformat.v4.new_code_cell("import time\ntime.sleep(600)")]
    path = tmp_path / "hangs.ipynb"
    nbformat.write(nb, path)
    start = time.monotonic()
    completed = subprocess.run(
        [sys.executable, str(ROOT / "book" / "_ext" / "execute_book.py"), "--timeout", "3",
         "--path-output", str(tmp_path / "out"), str(path)],
        capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert completed.returncode == 1
    assert time.monotonic() - start < 60
    assert "hangs.ipynb: cell 2 hung (more than 3 s)" in completed.stderr
    assert "time.sleep(600)" in completed.stderr


def test_cells_tagged_skip_execution_are_not_executed(tmp_path):
    import subprocess
    import sys

    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nb.cells = [nbformat.v4.new_code_cell("raise SystemExit('this cell must not run')"),
                nbformat.v4.new_code_cell("print('ran')")]
    nb.cells[0].metadata["tags"] = ["skip-execution", "remove-cell"]
    path = tmp_path / "skips.ipynb"
    nbformat.write(nb, path)
    out = tmp_path / "out"
    completed = subprocess.run(
        [sys.executable, str(ROOT / "book" / "_ext" / "execute_book.py"), "--path-output",
         str(out), str(path)], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert completed.returncode == 0, completed.stdout + completed.stderr

    from jupyter_cache import get_cache

    cache = get_cache(str(out / "_build" / ".jupyter_cache"))
    record = cache.match_cache_notebook(nbformat.read(path, as_version=4))  # the build's lookup
    executed = cache.get_cache_bundle(record.pk).nb
    assert executed.cells[0].execution_count is None and executed.cells[0].outputs == []
    assert executed.cells[1].execution_count == 1
    assert executed.cells[1].outputs[0]["text"] == "ran\n"


@pytest.mark.book
def test_the_install_cell_is_neither_executed_nor_shown_by_the_build(built_book):
    from jupyter_cache import get_cache
    from test_launch import INSTALL_CELL

    # The outputs the build used: those of the execution cache (the build executed no
    # notebook itself, built_book checks).
    cache = get_cache(str(built_book.parent / ".jupyter_cache"))
    for path in NOTEBOOKS:
        record = cache.match_cache_notebook(nbformat.read(path, as_version=4))
        executed = cache.get_cache_bundle(record.pk).nb
        install = executed.cells[0]
        assert install.source == INSTALL_CELL
        assert install.execution_count is None and install.outputs == [], path.name
        code = [c for c in executed.cells if c.cell_type == "code"]
        assert code[1].execution_count == 1, f"{path.name}: the kernel ran something before"
        html = (built_book / "book" / f"{path.stem}.html").read_text()
        for line in ("install icm when it is missing", "ICM_SOURCE", "find_spec"):
            assert line not in html, f"{path.name}: the install cell is shown"


@pytest.mark.book
def test_book_builds_with_every_chapter_and_figure(built_book):
    for name in toc_files():
        page = built_book / f"{name}.html"
        assert page.exists(), f"missing page {page}"
        html = page.read_text()
        assert "Traceback" not in html and "output traceback" not in html, f"error in {page}"
    for path in NOTEBOOKS:
        notebook = nbformat.read(path, as_version=4)
        expected = sum(1 for c in notebook.cells
                       if c.cell_type == "code" and "figure" in c.metadata.get("mystnb", {}))
        html = (built_book / "book" / f"{path.stem}.html").read_text()
        assert html.count("<img") >= expected, f"{path.name}: a figure did not render"
        assert "&lt;Figure size" not in html, f"{path.name}: a figure rendered as text"


def public_objects():
    """Every public class and function of the package, as "module.name" where it is
    defined: those of public modules, and those of private modules (a name part
    starting with "_") that a public package re-exports."""
    import importlib
    import inspect
    import pkgutil

    import icm

    found = set()
    for info in pkgutil.walk_packages(icm.__path__, "icm."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if name.startswith("_") or not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue
            if obj.__module__ != info.name:
                continue
            private = any(part.startswith("_") for part in info.name.split("."))
            package = importlib.import_module(info.name.rsplit(".", 1)[0])
            if not private or getattr(package, name, None) is obj:
                found.add(f"{info.name}.{name}")
    return found


@pytest.mark.book
def test_api_reference_covers_every_public_class_and_function(built_book):
    html = (built_book / "book" / "api.html").read_text()
    objects = public_objects()
    assert len(objects) > 40
    missing = sorted(name for name in objects if f'id="{name}"' not in html)
    assert missing == [], f"not in the API reference: {missing}"


@pytest.mark.book
def test_chapters_have_launch_and_download_buttons(built_book):
    config = yaml.safe_load((ROOT / "_config.yml").read_text())
    repository = config["repository"]["url"].removeprefix("https://github.com/")
    for path in NOTEBOOKS:
        html = (built_book / "book" / f"{path.stem}.html").read_text()
        assert f"mybinder.org/v2/gh/{repository}/main?urlpath=lab/tree/book/{path.name}" in html
        assert f"colab.research.google.com/github/{repository}/blob/main/book/{path.name}" in html
        assert f"_sources/book/{path.name}" in html  # the notebook download button
