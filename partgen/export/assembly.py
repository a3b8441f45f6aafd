"""The report's assembly steps for any kit: the mechanism's own (``assembly_steps(spec, kit)``, see
``core.protocol.Mechanism``) or, for a mechanism without them, a generic order (the base first, then
every printed part in the kit's order, the bought parts last); each step shown with the pictures of
the parts it uses."""

from __future__ import annotations

import html

from ..core.protocol import Kit, Step
from . import report as R

__all__ = ["default_steps", "steps_of", "assembly_section"]


def default_steps(kit: Kit) -> list[Step]:
    """A generic order: the base(s) first, then each printed part in the kit's order, the bought parts
    last (a part the kit prints several times — the same solid — is one step)."""
    base = [p.name for p in kit.parts if p.printed and p.role.endswith("base")]
    steps: list[Step] = [("Stand the base on the table.", tuple(base))] if base else []
    by_solid: dict[int, list[str]] = {}
    roles = {}
    for p in kit.parts:
        if p.printed and p.name not in base:
            by_solid.setdefault(id(p.solid), []).append(p.name)
            roles[id(p.solid)] = p.role.replace("_", " ")
    for key, names in by_solid.items():
        steps.append((f"Fit {' and '.join(names) if len(names) < 3 else ', '.join(names)} ({roles[key]}) in "
                      "its place on what stands already.", tuple(names)))
    bought = tuple(p.name for p in kit.parts if not p.printed)
    if bought:
        steps.append(("Fit the bought parts.", bought))
    return steps


def steps_of(mechanism, spec, kit: Kit) -> list[Step]:
    """The mechanism's assembly steps, or ``default_steps``; every part named must be the kit's."""
    own = getattr(mechanism, "assembly_steps", None)
    steps = [(text, tuple(names)) for text, names in (own(spec, kit) if own else default_steps(kit))]
    known = {p.name for p in kit.parts}
    unknown = [n for _, names in steps for n in names if n not in known]
    if unknown:
        raise ValueError(f"assembly steps name parts the kit does not have: {unknown}")
    return steps


def assembly_section(steps: list[Step], pictures: dict[str, bytes], printed_as: dict[str, str] | None = None
                     ) -> tuple[str, str]:
    """("Assembly", html): the steps in order, each with the pictures of its parts (``pictures``:
    part name -> PNG; a part without one is named only; ``printed_as``: a copy's name -> the name the
    bill lists it under, said in its caption)."""
    items = []
    alias = printed_as or {}

    def caption(n: str) -> str:
        return html.escape(n) + (f" <small>(a {html.escape(alias[n])})</small>" if n in alias else "")
    for text, names in steps:
        figs = "".join(f"<figure>{R.img(pictures[n], n, width=120) if n in pictures else ''}"
                       f"<figcaption>{caption(n)}</figcaption></figure>" for n in names)
        items.append(f'<li><p>{html.escape(text)}</p><div class="grid">{figs}</div></li>')
    return ("Assembly", f'<ol class="steps">{"".join(items)}</ol>')
