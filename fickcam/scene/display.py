"""How a loaded :class:`~fickcam.scene.load.Scene` shows itself: a few lines of text (``repr``)
and an HTML table in a notebook, each value as the user wrote it (``60 d``, ``113 degC``),
never the SI floats of the validated model."""
from __future__ import annotations

import html

import yaml

#: the sections shown after the parts, in order, with their headings
SECTIONS = (("materials", "materials"), ("environment", "climate"), ("outputs", "outputs"),
            ("limits", "limits"))

#: the longest value of the text repr [characters]; the HTML table shows all
WIDTH = 96


def flow(value) -> str:
    """``value`` in YAML's one-line flow style, as written: ``{plastic: nylon}``.

    Parameters
    ----------
    value : object
        A scalar, list or mapping read from a scene.

    Returns
    -------
    str
        The text.
    """
    if isinstance(value, str):
        return value
    text = yaml.safe_dump(value, default_flow_style=True, width=float("inf"), sort_keys=False)
    return text.strip().removesuffix("...").strip()


def entries(value) -> str:
    """A section as written, its entries in one line without the outer braces:
    ``cfrp: {fiber: T300, matrix: 8551-7}, steel: {metal: steel}``.

    Parameters
    ----------
    value : object
        A section of a scene (a mapping; anything else as :func:`flow` writes it).

    Returns
    -------
    str
        The text.
    """
    if isinstance(value, dict) and value:
        return ", ".join(f"{key}: {flow(entry)}" for key, entry in value.items())
    return flow(value)


def segment(step) -> str:
    """A climate segment in words: ``60 d at 113 degC, 80 % RH`` (else as written).

    Parameters
    ----------
    step : dict
        One entry of ``environment.history``.

    Returns
    -------
    str
        The text.
    """
    keys = {"duration", "temperature", "relative_humidity"}
    if isinstance(step, dict) and keys <= set(step) and set(step) <= keys | {"ramp"}:
        ramp = "ramp over " if step.get("ramp") else ""
        return (f"{ramp}{step['duration']} at {step['temperature']}, "
                f"{step['relative_humidity']} RH")
    return flow(step)


def parts(data: dict) -> list[tuple[str, str]]:
    """The mechanism's parts as written: the cam and its follower, or the four-bar.

    Parameters
    ----------
    data : dict
        The scene as written.

    Returns
    -------
    list of tuple of (str, str)
        (``cam``, its keys but the follower), (``follower``, ...) or (``linkage``, ...).
    """
    said = []
    cam = data.get("cam")
    if isinstance(cam, dict):
        said.append(("cam", entries({k: v for k, v in cam.items() if k != "follower"})))
        if "follower" in cam:
            said.append(("follower", entries(cam["follower"])))
    if "linkage" in data:
        said.append(("linkage", entries(data["linkage"])))
    return said


def climate(data: dict) -> str:
    """The climate history as written, segment by segment.

    Parameters
    ----------
    data : dict
        The scene as written.

    Returns
    -------
    str
        ``60 d at 113 degC, 80 % RH`` (segments joined by ``, then``), or the section
        as written when it is a record or a weather file.
    """
    environment = data.get("environment") or {}
    history = environment.get("history") if isinstance(environment, dict) else None
    if isinstance(history, list):
        return "; then ".join(segment(step) for step in history)
    return entries(environment)


def rows(data: dict) -> list[tuple[str, str]]:
    """(heading, text) of each section the scene has, as written.

    Parameters
    ----------
    data : dict
        The scene as written.

    Returns
    -------
    list of tuple of (str, str)
        In the order of :data:`SECTIONS`.
    """
    texts = {"environment": climate(data)}
    found = parts(data)
    for key, heading in SECTIONS:
        text = texts[key] if key in texts else entries(data[key]) if key in data else ""
        if text:
            found.append((heading, text))
    return found


def short(text: str, width: int = WIDTH) -> str:
    """``text`` cut to ``width`` characters with an ellipsis.

    Parameters
    ----------
    text : str
        The text.
    width : int
        The most characters kept [1].

    Returns
    -------
    str
        The text, or its start and ``…``.
    """
    return text if len(text) <= width else text[:width - 1] + "…"


def scene_text(name: str, source: str, data: dict) -> str:
    """A scene's text repr: a header and one line per section.

    Parameters
    ----------
    name : str
        The scene's name.
    source : str
        Its file (or ``<dict>``).
    data : dict
        The scene as written.

    Returns
    -------
    str
        The lines.
    """
    lines = [f"<fickcam Scene {name!r} from {source}>"]
    lines += [f"  {heading + ':':<11}{short(text)}" for heading, text in rows(data)]
    return "\n".join(lines)


def scene_html(name: str, source: str, data: dict) -> str:
    """A scene's HTML repr: its name, file and description, and a table of its sections.

    Parameters
    ----------
    name : str
        The scene's name.
    source : str
        Its file (or ``<dict>``).
    data : dict
        The scene as written.

    Returns
    -------
    str
        The HTML.
    """
    description = data.get("description") or ""
    cells = "".join(
        f'<tr><th style="text-align:left;vertical-align:top">{html.escape(heading)}</th>'
        f'<td style="text-align:left"><code>{html.escape(text)}</code></td></tr>'
        for heading, text in rows(data))
    caption = (f"<b>fickcam Scene</b> <code>{html.escape(name)}</code> from "
               f"<code>{html.escape(source)}</code>"
               + (f"<br/>{html.escape(str(description))}" if description else ""))
    return f'<div><p>{caption}</p><table>{cells}</table></div>'
