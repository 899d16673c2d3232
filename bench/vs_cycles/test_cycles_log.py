"""Cycles' render times are read from its log, not from the truncated EXR stamp."""
import pytest

from bench.vs_cycles import cycles_log

# Two renders as Blender 3.4 logs them with --debug-cycles --verbose 2 (stderr, abridged).
LOG = """I1205 06:52:40.461180 13973 path_trace.cpp:404] Rendered 15 samples in 0.021718 seconds
I1205 06:52:40.463404 13973 session.cpp:156] Rendering in main loop is done in 0.0276449 seconds.
I1205 06:52:40.463941 13957 session.cpp:464] Total render time: 0.074604
I1205 06:52:40.463991 13957 session.cpp:465] Render time (without synchronization): 0.0281689
I1205 06:52:48.741303 14045 session.cpp:464] Total render time: 0.936931
I1205 06:52:48.741346 14045 session.cpp:465] Render time (without synchronization): 0.9086
"""


def test_each_render_gives_its_render_and_total_time_in_order():
    assert cycles_log.render_times(LOG) == [(0.0281689, 0.074604), (0.9086, 0.936931)]


def test_the_stamp_is_the_time_truncated_to_hundredths():
    # What Blender wrote into the EXRs of these two renders: 00:00.02 and 00:00.90.
    assert cycles_log.agrees_with_stamp(0.0281689, 0.02)
    assert cycles_log.agrees_with_stamp(0.9086, 0.90)
    # A log line paired with another render's stamp is caught.
    assert not cycles_log.agrees_with_stamp(0.0281689, 0.09)
    assert not cycles_log.agrees_with_stamp(0.9086, 0.88)


def test_a_log_with_a_missing_line_is_an_error():
    with pytest.raises(ValueError):
        cycles_log.render_times(LOG + "I1205 session.cpp:464] Total render time: 1.0\n")
