"""Mode shapes and node lines, free against hand-held."""

from __future__ import annotations

import math
from typing import Any

from racketdyn.plotting.registry import file_of, labelled
from racketdyn.report.folder import RunFolder, number, read_csv
from racketdyn.report.formatting import fmt

HOW_TO_RUN = "racketdyn compare DIR/frf_free/frfs.uff DIR/frf_hand/frfs.uff --out DIR/compare"


def gather(run: RunFolder) -> dict[str, Any] | None:
    """Figs 4–6 of every identification, and ``racketdyn compare``'s pairing of the modes
    (``comparison.csv``) with the first mode's nodes along the axis."""
    idents = run.identifications
    if not idents:
        return None
    shapes = run.group(
        [
            (folder / labelled("fig4_mode_shapes", suffix), label)
            for label, folder, suffix in idents
        ],
        "plain",
        wide=True,
    )
    node_lines = run.group(
        [(folder / labelled("fig5_node_lines", suffix), label) for label, folder, suffix in idents]
    )
    compare = run.mode_comparison_dir
    overlay = compare / file_of("fig6_nodes_free_hand") if compare else None
    if overlay is not None and overlay.is_file():
        nodes = run.group([(overlay, "")])
    else:
        nodes = run.group(
            [(folder / labelled("fig6_nodes", suffix), label) for label, folder, suffix in idents],
            "pair",
        )
    pairs: list[tuple[str, ...]] = []
    first_nodes: list[tuple[str, str]] = []
    glance = []
    comparison = None
    if compare is not None:
        rows = read_csv(
            compare / "comparison.csv", ("mode", "frequency_free_hz", "frequency_hand_hz")
        )
        pairs = [
            (
                r.get("mode", ""),
                fmt(number(r, "frequency_free_hz"), ".2f"),
                fmt(number(r, "frequency_hand_hz"), ".2f"),
                fmt(number(r, "frequency_shift_percent"), "+.2f"),
                fmt(100 * number(r, "damping_free"), ".3f"),
                fmt(100 * number(r, "damping_hand"), ".3f"),
                fmt(number(r, "damping_ratio_hand_over_free"), ".2f"),
                fmt(number(r, "mac"), ".3f"),
                r.get("note") or "",
            )
            for r in rows
        ]
        first_nodes = [
            (support, ", ".join(f"{v * 1e3:.0f}" for v in values))
            for support, values in run.first_mode_nodes().items()
        ]
        paired = [r for r in rows if math.isfinite(number(r, "mac"))]
        if paired:
            first = paired[0]
            glance.append(
                f"{first.get('mode', 'first mode')}: "
                f"{fmt(number(first, 'frequency_free_hz'), '.1f')} Hz "
                f"free, {fmt(number(first, 'frequency_hand_hz'), '.1f')} Hz hand-held "
                f"({fmt(number(first, 'frequency_shift_percent'), '+.1f')} %), damping "
                f"×{fmt(number(first, 'damping_ratio_hand_over_free'), '.1f')} in the hand"
            )
        comparison = run.group([(compare / file_of("comparison"), "")])
    if not (shapes or node_lines or nodes or compare):
        return None
    return {
        "shapes": shapes,
        "node_lines": node_lines,
        "nodes": nodes,
        "compared": compare is not None,
        "pairs": pairs,
        "first_nodes": first_nodes,
        "comparison": comparison,
        "glance": glance,
    }
