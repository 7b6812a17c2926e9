"""Bad input raises the Python exception of its kind with the command line's one line, writes
nothing and never takes the interpreter down."""

import pytest

import retrace
from conftest import SMALL, run_cli


def cli_error(binary, *args):
    """The line `retrace <args>` prints on stderr, without "retrace: error: "."""
    done = run_cli(binary, *args)
    assert done.returncode == 2, done.stderr
    line = done.stderr.strip()
    assert line.startswith("retrace: error: ") and "\n" not in line, line
    return line[len("retrace: error: "):]


def test_an_unknown_key_is_a_value_error_naming_it(tmp_path, retrace_binary):
    with pytest.raises(ValueError) as error:
        retrace.run(SMALL, set="nav.localizer.particlez=10", out=tmp_path / "out")
    assert error.value.key.startswith("nav.localizer.particlez")
    assert str(error.value) == cli_error(retrace_binary, "run", SMALL, "--set",
                                         "nav.localizer.particlez=10", "--out", tmp_path / "c")
    assert not (tmp_path / "out").exists() and not (tmp_path / "c").exists()


def test_a_bad_value_is_a_value_error_naming_its_key(tmp_path):
    with pytest.raises(ValueError, match="particles") as error:
        retrace.teach(SMALL, set={"nav.localizer.particles": -5}, out=tmp_path / "out")
    assert "particles" in error.value.key
    assert not (tmp_path / "out").exists()


def test_a_missing_scenario_is_file_not_found(tmp_path, retrace_binary):
    missing = tmp_path / "missing.yaml"
    with pytest.raises(FileNotFoundError) as error:
        retrace.run(missing, out=tmp_path / "out")
    assert str(error.value) == cli_error(retrace_binary, "run", missing)
    with pytest.raises(FileNotFoundError):
        retrace.log_info(tmp_path / "missing.mcap")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("call, message", [
    (lambda: retrace.run(42), "incompatible function arguments"),
    (lambda: retrace.run(SMALL, modes=3), "modes: must be a str or a list of str"),
    (lambda: retrace.run(SMALL, modes=["partial", 1]), "modes: must hold str"),
    (lambda: retrace.run(SMALL, seed="1"), "seed: must be an int"),
    (lambda: retrace.run(SMALL, seed=True), "seed: must be an int"),
    (lambda: retrace.run(SMALL, repeats=1.5), "repeats: must be an int"),
    (lambda: retrace.run(SMALL, set=7), "set: must be"),
    (lambda: retrace.run(SMALL, progress=5), "progress: must be None, False or a callable"),
    (lambda: retrace.log_localize("x.mcap", teach="t", out="o", initial_pose="1,2,3"),
     "incompatible function arguments"),
])
def test_a_wrong_type_is_a_type_error(call, message):
    with pytest.raises(TypeError, match=message):
        call()


@pytest.mark.parametrize("kwargs, key, message", [
    ({"seed": -1}, "seed", "seed: must be an integer from 0 to 9223372036854775807, got '-1'"),
    ({"seed": 2**64}, "seed", "got '18446744073709551616'"),
    ({"repeats": 0}, "repeats", "repeats: must be a number > 0, got '0'"),
    ({"jobs": -2}, "jobs", "jobs: must be a number >= 0, got '-2'"),
    ({"modes": "partial,bogus"}, "modes", "modes: "),
    ({"video_speed": 0.0}, "video_speed", "must be a number > 0"),
    # Checked by the library, which names the command line's option: `key` is the argument.
    ({"video": True, "video_run": 5}, "video_run", "--video-run: run 5 is not played back"),
])
def test_a_wrong_value_is_a_value_error_before_anything_runs(tmp_path, kwargs, key, message):
    with pytest.raises(ValueError) as error:
        retrace.run(SMALL, out=tmp_path / "out", **kwargs)
    assert error.value.key == key and message in str(error.value)
    assert not (tmp_path / "out").exists()


def test_an_output_that_is_a_file_is_an_os_error(tmp_path):
    (tmp_path / "file").write_text("")
    with pytest.raises(OSError, match="exists and is not a folder"):
        retrace.teach(SMALL, out=tmp_path / "file", progress=False)
