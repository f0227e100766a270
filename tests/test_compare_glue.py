"""benchmarks/compare_glue.py, the check that a change left the book's glued numbers as
they were: it finds a changed value, a missing one and a missing chapter, and sets the
machine's times apart."""

import importlib.util
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("compare_glue", ROOT / "benchmarks" / "compare_glue.py")
compare_glue = importlib.util.module_from_spec(spec)
spec.loader.exec_module(compare_glue)


def glue(folder, chapter, values):
    folder.mkdir(exist_ok=True)
    (folder / f"{chapter}.glue.json").write_text(json.dumps(
        {name: {"data": {"text/plain": repr(value)}, "output_type": "display_data"}
         for name, value in values.items()}))


def test_the_comparison_lists_every_difference_and_only_those(tmp_path, capsys):
    before, after = tmp_path / "before", tmp_path / "after"
    glue(before, "rod_toppling", {"red_first": 0.93, "n_seeds": 200, "physics_seconds": 11.7,
                                  "physics_ms_per_move": 21.9})
    glue(after, "rod_toppling", {"red_first": 0.93, "n_seeds": 200, "physics_seconds": 12.4,
                                 "physics_ms_per_move": 23.0})
    glue(before, "curiosity", {"noisy": 0.5})
    glue(after, "curiosity", {"noisy": 0.5})
    assert compare_glue.main([str(before), str(after)]) == 0
    assert "5 glued values compared; 0 differ, 2 more differ as expected" in \
        capsys.readouterr().out

    glue(after, "curiosity", {"noisy": 0.51, "new": 1})
    assert compare_glue.main([str(before), str(after)]) == 1
    out = capsys.readouterr().out
    assert "DIFFERS  curiosity.noisy: text/plain '0.5' -> '0.51'" in out
    assert "DIFFERS  curiosity.new: glued only after" in out

    (after / "curiosity.glue.json").unlink()
    assert compare_glue.main([str(before), str(after)]) == 1
    assert "DIFFERS  curiosity: only in before" in capsys.readouterr().out
