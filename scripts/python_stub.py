"""Writes the keyword options of the package's type stubs (surfcomp/__init__.pyi) from the
library's option tables, as the built module gives them, so that the stubs cannot drift from the
tables. Each stubbed function made with the tables (``_keyword_options``) gets one line per option
of its table, in the table's order, after the parameters written by hand (the positional ones,
``*`` and keywords of its own such as ``report``). tests/python/test_module.py checks that the
stubs are current.

    PYTHONPATH=build/ci/python /usr/bin/python3 scripts/python_stub.py [--check]

--check: print the differences and exit 1 instead of writing."""
import difflib
import pathlib
import re
import sys

import surfcomp

STUB = pathlib.Path(__file__).resolve().parents[1] / "python" / "surfcomp" / "__init__.pyi"

# The module takes a text option as str or os.PathLike (os.fsdecode), so PathLike, which is both.
_TYPES = {"real": "float", "integer": "int", "text": "PathLike", "choice": "str", "flag": "bool",
          "spheres": "SiteSpheres"}
_DEFINITION = re.compile(r"^def (\w+)\(\n(.*?)^\)( -> [^\n]*)$", re.M | re.S)
_PARAMETER = re.compile(r"^    (\w+)\b")


def option_line(option):
    """The stub's line of one option of a table (surfcomp.option_table)."""
    annotation = _TYPES[option["kind"]]
    if option["default"] is None:
        annotation = f"Optional[{annotation}]"
    return f"    {option['name']}: {annotation} = {option['default']!r},\n"


def generated(stub):
    """`stub` with the options of every table-made function written from its table."""
    def rewrite(found):
        name, parameters, rest = found.groups()
        table_name = getattr(getattr(surfcomp, name, None), "_option_table", None)
        if table_name is None:
            return found.group(0)
        table = surfcomp.option_table(table_name)
        options = {o["name"] for o in table}
        own = [line for line in parameters.splitlines(keepends=True)
               if not (_PARAMETER.match(line) and _PARAMETER.match(line).group(1) in options)]
        return (f"def {name}(\n" + "".join(own) + "".join(option_line(o) for o in table) + ")"
                + rest)

    return _DEFINITION.sub(rewrite, stub)


def main(arguments):
    current = STUB.read_text()
    wanted = generated(current)
    if "--check" in arguments:
        if current != wanted:
            sys.stdout.writelines(difflib.unified_diff(
                current.splitlines(keepends=True), wanted.splitlines(keepends=True),
                str(STUB), "generated"))
            return 1
        return 0
    if current != wanted:
        STUB.write_text(wanted)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
