"""job_log: a workflow job's log names what it read and wrote, its time, warnings and failures."""

import logging
import warnings

import pytest

from rotbeam.report.joblog import job_log


def test_log_names_inputs_outputs_and_time(tmp_path):
    src, out, log_file = tmp_path / "in.csv", tmp_path / "out.csv", tmp_path / "logs" / "j.log"
    src.write_text("a\n1\n")
    with job_log(log_file, [src], [out, tmp_path / "never.csv"], "rule_x") as log:
        log.info("step %d", 1)
        logging.getLogger("matplotlib.mathtext").info("font note")  # another library's chatter
        warnings.warn("something odd", RuntimeWarning, stacklevel=1)
        out.write_text("b\n2\n")
    text = log_file.read_text()
    assert f"read {src} (4 bytes)" in text and "step 1" in text
    assert f"wrote {out} (4 bytes)" in text and f"wrote {tmp_path / 'never.csv'} (missing)" in text
    assert "RuntimeWarning: something odd" in text and "font note" not in text
    assert "rule_x: done in" in text
    # the logging set-up is undone
    ours = [
        h for h in logging.getLogger().handlers if getattr(h, "baseFilename", "") == str(log_file)
    ]
    assert not ours


def test_a_failure_lands_in_the_log_and_propagates(tmp_path):
    log_file = tmp_path / "j.log"
    with pytest.raises(ZeroDivisionError), job_log(log_file, [], [], "rule_y"):
        1 / 0  # noqa: B018
    text = log_file.read_text()
    assert "rule_y failed after" in text and "ZeroDivisionError" in text and "Traceback" in text
    assert "done in" not in text
