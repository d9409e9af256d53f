"""What a first run shows: every figure the bearing scenes write (smoke runs of the README's main job, the
cage-less rotor drop, and of the tapered roller bearing of paper A) has each of its titles, labels and
notes inside the figure (matplotlib's own layout: the window extent of every drawn text artist after
``fig.canvas.draw()``, against the figure's bounding box) and no two neighbouring tick labels overlap, a Poincare section with too few points says
so on the figure and in the summary, the phase portraits show the frame turning with the ball train
beside the fixed frame, and ``lubedyn run`` prints only what was computed."""
from __future__ import annotations

import math

import numpy as np
import pytest

import lubedyn
from lubedyn import outputs
from lubedyn.papers.zhang2024 import figures as pb


def _captured_run(monkeypatch, tmp_path, name, overrides=(), only=None):
    """Run a bundled case at smoke size into ``tmp_path``; ``({file: clipped texts}, {file: figure}, result)``,
    the figures checked as ``save_figure`` receives them (before they are closed); ``only``: the file names
    to check (each check draws the figure three times), None for all."""
    import matplotlib

    matplotlib.use("Agg")
    clipped, figures = {}, {}
    save = outputs.save_figure

    def check_then_save(path, figure, dpi=120):
        if only is not None and path.name not in only:
            return save(path, figure, dpi)
        figure.set_dpi(dpi)
        clipped[path.name] = _clipped_texts(figure) + _overlapping_ticks(figure)
        figures[path.name] = _texts(figure)
        return save(path, figure, dpi)

    monkeypatch.setattr(outputs, "save_figure", check_then_save)
    # the figures drawn in this process (a forked worker's would not reach these dicts; the workers write the
    # same bytes: tests/test_output_workers.py)
    monkeypatch.setenv("LUBEDYN_OUTPUT_WORKERS", "0")
    case = lubedyn.load_case(name, smoke=True, overrides=overrides)
    result = lubedyn.run(case, tmp_path / name, smoke=True)
    return clipped, figures, result


def _drawn_texts(figure):
    """(name, window extent) of every drawn text: titles, labels, notes, legends one by one; each axis
    (its drawn tick labels, offset text and label) as one box, from the axis' own extent, since tick
    labels outside the view limits exist as artists but are not drawn."""
    from matplotlib.text import Text

    renderer = figure.canvas.get_renderer()
    ticks = set()
    for ax in figure.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                ticks.update((id(tick.label1), id(tick.label2)))
            ticks.update((id(axis.label), id(axis.offsetText)))
            box = axis.get_tightbbox(renderer)
            if box is not None and box.width > 0:
                yield f"{axis.axis_name} axis of {axis.label.get_text() or ax.get_title() or 'an axes'}", box
    for text in figure.findobj(Text):
        if id(text) in ticks or not text.get_visible() or not text.get_text().strip():
            continue
        yield text.get_text(), text.get_window_extent(renderer)


def _draw(figure):
    if not hasattr(figure.canvas, "get_renderer"):  # a Figure made without pyplot: give it the Agg canvas
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(figure)
    figure.canvas.draw()


def _texts(figure) -> list[str]:
    _draw(figure)
    return [t for t, _ in _drawn_texts(figure)]


def _clipped_texts(figure) -> list[str]:
    """The drawn texts whose extent leaves the figure by more than one pixel."""
    _draw(figure)
    box = figure.bbox
    return [f"{t!r} at ({b.x0:.0f}, {b.y0:.0f})-({b.x1:.0f}, {b.y1:.0f}) of {box.width:.0f}x{box.height:.0f}"
            for t, b in _drawn_texts(figure)
            if b.x0 < box.x0 - 1 or b.y0 < box.y0 - 1 or b.x1 > box.x1 + 1 or b.y1 > box.y1 + 1]


@pytest.fixture(scope="session")
def drop(tmp_path_factory):
    """One smoke drop per test process, its figures checked as they are saved.  Session-scoped, with the
    patches undone as soon as the run ends: pytest-xdist's worksteal interleaves this module's tests with
    other modules', and a module-scoped fixture was set up again after each interleaving (3-4 runs of
    11-13 s each in a full run, where one per worker is needed)."""
    mp = pytest.MonkeyPatch()
    try:
        return _captured_run(mp, tmp_path_factory.mktemp("drop"), "cageless_6206_10krpm_short")
    finally:
        mp.undo()


def _overlapping_ticks(figure) -> list[str]:
    """Neighbouring drawn major tick labels of one axis that overlap (long labels such as -23.0125 on a
    narrow axis)."""
    _draw(figure)
    renderer = figure.canvas.get_renderer()
    found = []
    for ax in figure.axes:
        for axis, lim in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            lo, hi = sorted(lim)
            tol = 1e-9 * (hi - lo)
            shown = [(loc, label) for loc, label in zip(axis.get_majorticklocs(), axis.get_majorticklabels())
                     if lo - tol <= loc <= hi + tol and label.get_visible() and label.get_text()]
            boxes = [(label.get_text(), label.get_window_extent(renderer)) for _, label in sorted(shown, key=lambda p: p[0])]
            for (a, box_a), (b, box_b) in zip(boxes, boxes[1:]):
                if box_a.overlaps(box_b):
                    found.append(f"{axis.axis_name} ticks {a!r} and {b!r} of {axis.label.get_text()!r}")
    return found


def test_cageless_figures_not_clipped(drop):
    clipped, figures, result = drop
    assert set(clipped) == {"trajectories.png", "collision_needles.png", "phase_portraits.png", "spectrum.png",
                            "angular_displacement.png", "collision_map.png", "poincare.png"}
    assert {name: texts for name, texts in clipped.items() if texts} == {}


def test_tapered_figures_not_clipped(monkeypatch, tmp_path):
    clipped, _, _ = _captured_run(monkeypatch, tmp_path, "trb_fig5_2400rpm")
    assert clipped, "the tapered scene wrote no figure"
    assert {name: texts for name, texts in clipped.items() if texts} == {}


def test_clip_check_finds_a_cut_title():
    """The checks themselves: a title wider than its figure is reported, the same title wrapped is not;
    overlapping tick labels are reported, fewer ticks are not."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    long = "a case description far longer than a four-inch figure is wide, as a user may well write one " * 2
    fig, ax = plt.subplots(figsize=(4, 3), layout="constrained")
    ax.set_title(long)
    assert len(_clipped_texts(fig)) == 1
    import textwrap

    ax.set_title(textwrap.fill(long, 40), fontsize=8)
    assert _clipped_texts(fig) == []
    ax.set_xlim(-23.02, -23.0095)           # a ball's y near -23 mm: nine long tick labels on four inches
    ax.set_xticks(np.linspace(-23.02, -23.01, 9))
    assert len(_overlapping_ticks(fig)) >= 1
    ax.locator_params(axis="x", nbins=3)
    assert _overlapping_ticks(fig) == []
    plt.close(fig)


def test_short_poincare_section_says_so(drop):
    """The 1 ms smoke run: ball 0 orbits at about 0.4 of the ring's speed, once per tens of ms, so the section
    has no point; the summary and the figure both say so, with the record length that would give ten."""
    _, figures, result = drop
    s = result.summary
    assert s["Poincare points, ball 0 [-]"] < pb.POINCARE_MIN_POINTS
    note = s["Poincare points, ball 0, note"]
    assert note.startswith("poincare.png is not a section yet: only ")
    assert any(t.startswith("too few points for a section") for t in figures["poincare.png"])
    # the period in the note (from the unwrapped azimuth) against the mean of the ball's orbital speed column
    period_ms = float(note.split("one per orbit, ")[1].split(" ms")[0])
    folder = next(p.parent for p in result.files if p.name == "summary.json")
    columns, _ = outputs.read_timeseries(outputs.timeseries_path(folder))
    omega = float(np.mean(columns["Ball 0 Orbital speed [rad/s]"]))
    assert period_ms == pytest.approx(2e3 * math.pi / omega, rel=0.01)


def test_poincare_shortfall_counts():
    """A ball on a uniform orbit of period 2 ms over 5 ms: 2 points are short of 10 by a record of 20 ms."""
    t = np.linspace(0.0, 5e-3, 5001)
    azimuth = 2 * math.pi * t / 2e-3
    note = pb.poincare_shortfall(t, azimuth, 2)
    assert "2 ms at the ball's mean orbital speed" in note and "about 20 ms would give 10" in note
    assert pb.poincare_shortfall(t, azimuth, 10) is None


def test_phase_portraits_show_both_frames(drop):
    _, figures, _ = drop
    texts = figures["phase_portraits.png"]
    assert "fixed (inertial) frame: the orbit dominates x and y" in texts
    assert "frame turning with the ball train: orbit removed" in texts


def test_terminal_prints_only_what_was_computed(drop):
    """The headline of the smoke main job: no "not computed" line, and one count of what is missing, equal to
    the quantities of the summary that have a value of None or "not computed" and a note saying why."""
    from lubedyn.scenes import dynamics

    _, _, result = drop
    s = result.summary
    lines = dynamics.headline(s)
    assert not any("not computed" in line and "quantities not computed" not in line for line in lines)
    missing = {k.rpartition(" [")[0] for k, v in s.items()
               if v is None and (k.startswith("Wolf exponent") or "Lyapunov exponent" in k)}
    assert missing, "the 1 ms smoke run computes every chaos estimator: pick another case for this test"
    assert all(isinstance(s.get(f"{k}, note"), str) and s[f"{k}, note"].startswith("not computed") for k in missing)
    assert lines[-1].startswith(f"{len(missing)} quantities not computed")
    for key in dynamics.HEADLINE:
        if outputs.computed(s.get(key)):
            assert any(line.startswith(key) for line in lines), key


def test_too_short_a_record_for_a_spectrum_says_so(monkeypatch, tmp_path):
    """The transient moved to 0.99 ms of the 1 ms smoke record (2 us samples): 6 samples are left, too few for
    the spectrum; the figure says so where the spectrum would be, and the summary's dominant frequency is None
    with the same reason."""
    _, figures, result = _captured_run(monkeypatch, tmp_path, "cageless_6206_10krpm_short",
                                       ["analysis.transient=0.99 ms", 'output.write=["png"]'], only={"spectrum.png"})
    assert "no spectrum: 6 samples after analysis.transient = 0.00099 s (at least 16 needed)" in figures["spectrum.png"]
    key = next(k for k in result.summary if k.startswith("Dominant inner ring acceleration frequency") and k.endswith(", note"))
    assert result.summary[key] == "not computed: fewer than 16 samples after the transient"
