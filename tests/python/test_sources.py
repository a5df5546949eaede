"""What the sources promise of themselves: the library's messages and help texts name options by
their fields (options::named, {field} in a help text), never by a front end's spelling, and each
field they name is an option the command line has; lists of file extensions come from the
format tables; each module includes only the modules it stands on."""
import re
import subprocess

from conftest import SOURCE_DIR

LIBRARY_MODULES = ("core", "mesh", "molsurf", "harmonic", "matching", "docking", "screening",
                   "report")
COMMANDS = ("surf-build", "cp-detect", "hsi-build", "match", "dock", "matrix", "screen",
            "screen --receptor R", "report", "pockets", "patch-map", "library build",
            "library info", "library export")

_LITERAL = re.compile(r'"(?:[^"\\\n]|\\.)*"')
_FLAG = re.compile(r"(?<![\w-])--[a-z]")


def _library_sources():
    for module in LIBRARY_MODULES:
        for path in sorted((SOURCE_DIR / module).rglob("*")):
            if path.suffix in (".cpp", ".hpp") and "node_modules" not in path.parts:
                yield path


def _literals(line):
    """The string literals of a line of C++ that come before its // comment."""
    out, start = [], 0
    for literal in _LITERAL.finditer(line):
        if "//" in line[start:literal.start()]:
            break
        out.append(literal.group(0))
        start = literal.end()
    return out


def test_library_messages_name_no_front_ends_flag():
    found = []
    for path in _library_sources():
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if line.lstrip().startswith("//"):
                continue
            found += [f"{path.relative_to(SOURCE_DIR)}:{number}: {literal}"
                      for literal in _literals(line) if _FLAG.search(literal)]
    assert not found, "library messages spell options as the command line does (use " \
        "options::named):\n" + "\n".join(found)


def test_lists_of_file_extensions_come_from_the_format_tables():
    # Two extensions in a row (".pdb .ent") in a library literal is a list written by hand: it
    # belongs to io::molecule_extensions or mesh::io::mesh_extensions.
    listed = re.compile(r"(?<![\w.])\.[a-z][a-z0-9]*(?:\.gz)? \.[a-z][a-z0-9]*\b")
    found = []
    for path in _library_sources():
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if line.lstrip().startswith("//"):
                continue
            found += [f"{path.relative_to(SOURCE_DIR)}:{number}: {literal}"
                      for literal in _literals(line) if listed.search(literal)]
    assert not found, "extension lists written by hand:\n" + "\n".join(found)


def test_each_option_a_message_names_is_one_the_command_line_has(program):
    fields = set()
    for path in _library_sources():
        for call in re.finditer(r"options::named\(((?:[^()]|\([^()]*\))*)\)", path.read_text()):
            fields |= set(re.findall(r'"([a-z0-9_]+)"', call.group(1)))
        for line in path.read_text().splitlines():  # help texts name them {field}
            for literal in _literals(line):
                fields |= set(re.findall(r"\{([a-z][a-z0-9_]*)\}", literal))
    ses = (SOURCE_DIR / "molsurf" / "src" / "ses.cpp").read_text()
    fields |= set(re.findall(r'require_(?:limit|within)\([^;]*?"([a-z0-9_]+)"\);', ses, re.S))
    assert {"repair", "unit", "max_vertices", "max_grid_cells", "refine_top"} <= fields, \
        sorted(fields)
    helps = "".join(subprocess.run([program, *command.split(), "--help"], capture_output=True,
                                   text=True, check=True).stdout for command in COMMANDS)
    missing = sorted(f for f in fields if "--" + f.replace("_", "-") not in helps)
    assert not missing, f"messages name options no command has: {missing}"


# Each module and what it may include (docs/architecture.md): the modules below it.
_STANDS_ON = {
    "core": (),
    "mesh": ("core",),
    "molsurf": ("core", "mesh"),
    "harmonic": ("core", "mesh"),
    "matching": ("core", "mesh", "molsurf", "harmonic"),
    "docking": ("core", "mesh", "molsurf", "harmonic", "matching"),
    "screening": ("core", "mesh", "molsurf", "harmonic", "matching", "docking"),
    "report": ("core", "mesh", "molsurf", "harmonic", "matching", "docking"),
}
_INCLUDE = re.compile(r'^#include "([^"]+)"', re.M)


def test_the_modules_include_only_what_they_stand_on():
    found = []
    for path in _library_sources():
        module = path.relative_to(SOURCE_DIR).parts[0]
        for header in _INCLUDE.findall(path.read_text()):
            parts = header.split("/")
            if parts[0] == "surfcomp" and parts[1] not in (module,) + _STANDS_ON[module]:
                found.append(f"{path.relative_to(SOURCE_DIR)} includes {header}")
    # The Python module's library side reaches the libraries, not the command line: only the
    # extension for `python3 -m surfcomp` includes tools/.
    tools_headers = {p.name for p in (SOURCE_DIR / "tools").glob("*.hpp")}
    for path in sorted((SOURCE_DIR / "python" / "src").glob("*.[ch]pp")):
        if path.name == "command_line.cpp":
            continue
        found += [f"{path.relative_to(SOURCE_DIR)} includes {header}"
                  for header in _INCLUDE.findall(path.read_text()) if header in tools_headers]
    # No code outside screening/ reaches the screen's internals (its src/ headers); tests may.
    internals = {p.name for p in (SOURCE_DIR / "screening" / "src").glob("*.hpp")}
    for path in sorted(SOURCE_DIR.rglob("*.[ch]pp")):
        relative = path.relative_to(SOURCE_DIR)
        if relative.parts[0] in ("screening", "tests", "build") or "node_modules" in relative.parts:
            continue
        found += [f"{relative} includes {header}" for header in _INCLUDE.findall(path.read_text())
                  if header in internals]
    assert not found, "includes against the layering:\n" + "\n".join(found)
