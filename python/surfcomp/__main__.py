"""``python3 -m surfcomp ...`` runs the surfcomp command line (the same subcommands, options,
messages and exit statuses as the ``surfcomp`` program)."""

import sys

from . import _command_line


def main() -> int:
    sys.stdout.flush()
    return _command_line.run_command_line(sys.argv[1:])


if __name__ == "__main__":
    sys.exit(main())
