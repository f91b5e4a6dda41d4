#!/usr/bin/env python3
"""Doxygen INPUT_FILTER for the public headers: shows their plain-text formulas as formulas.

The headers write a displayed formula as a doc-comment line indented by five or more spaces after
`///` (four beyond the usual one), e.g.
    /// trolley's traverse) since the state was initialized:
    ///     W(t) = integral from t0 to t of P_motion dt,   P_motion = SimbodyMatterSubsystem::calcMotionPower,
Markdown would run such a line into the paragraph above it. This filter turns each one into a line
of its own in a fixed-width font, keeping its spacing, and breaks the line after the last one; the
continuation lines of @param / @throws / @return / @tparam and of list items ("- ") are left alone.
It never adds or removes lines, so Doxygen's warnings keep the headers' line numbers.
"""
import re
import sys

DOC = re.compile(r"^(\s*///)(.*)$")
COMMAND = re.compile(r"^\s*[@\\](param|throws|throw|return|returns|tparam|retval|pre|post|note)\b")
LIST_ITEM = re.compile(r"^ {0,4}- ")  # deeper "- " lines are formulas (a leading minus sign)
ESCAPES = {".": "\\.", "&": "&amp;", "<": "&lt;", ">": "&gt;", " ": "&nbsp;", "\\": "\\\\", "@": "\\@",
           "*": "\\*", "|": "\\|", "#": "\\#", "%": "\\%", "$": "\\$"}


def formula(text):
    """The formula text as Doxygen copies it verbatim: non-breaking spaces, HTML entities and
    escaped Doxygen specials (an escaped period never ends a brief description)."""
    parts = text.split(" . ")  # the dot product: a centred dot
    return "&nbsp;&middot;&nbsp;".join("".join(ESCAPES.get(c, c) for c in part) for part in parts)


def filter_lines(lines):
    out = []
    in_block = False      # inside a command's or list item's continuation lines
    after_formula = False  # the previous doc line was a displayed formula
    for line in lines:
        m = DOC.match(line)
        if not m:
            in_block = after_formula = False
            out.append(line)
            continue
        prefix, body = m.group(1), m.group(2)
        indent = len(body) - len(body.lstrip(" "))
        text = body.strip()
        if text == "":
            in_block = after_formula = False
            out.append(line)
            continue
        if COMMAND.match(body) or LIST_ITEM.match(body):
            in_block = True     # a command or list item starts a new section: no break needed
            out.append(line)
        elif indent >= 5 and not in_block:
            # A displayed formula (four spaces beyond the one after ///): its own line, fixed
            # width, its further indentation kept.
            # A closing period stays outside the fixed-width text, so that a brief description
            # ending there (JAVADOC_AUTOBRIEF) does not cut the <tt> in two.
            end = "." if text.endswith(".") else ""
            shown = text[:-1] if end else text
            out.append(f"{prefix} <br><tt>{formula(' ' * (indent - 5) + shown)}</tt>{end}\n")
            after_formula = True
            continue
        else:
            if indent < 5:
                in_block = False
            out.append(f"{prefix} <br>{body.lstrip()}\n" if after_formula else line)
        after_formula = False
    return out


if __name__ == "__main__":
    with open(sys.argv[1], encoding="utf-8") as f:
        sys.stdout.write("".join(filter_lines(f.readlines())))
