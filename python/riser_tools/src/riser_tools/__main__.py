"""`riser-tools COMMAND [ARGS...]` (or `python -m riser_tools`): runs one study or tool; each
command's `--help` tells its options. Without a command: the list."""

from __future__ import annotations

import importlib
import sys
from collections.abc import Sequence


def main(argv: Sequence[str] | None = None) -> None:
    from .studies import COMMANDS
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] in ("-h", "--help") or args[0] not in COMMANDS:
        width = max(map(len, COMMANDS))
        lines = [f"  {name:<{width}}  {what}" for name, (_, what) in COMMANDS.items()]
        text = "usage: riser-tools COMMAND [ARGS...]\n\ncommands:\n" + "\n".join(lines)
        if args and args[0] not in ("-h", "--help"):
            sys.exit(f"riser-tools: unknown command {args[0]!r}\n\n{text}")
        print(text)
        return
    module, _ = COMMANDS[args[0]]
    entry = "package_main" if module == "riser_tools.fmu" else "main"
    rc = getattr(importlib.import_module(module), entry)(args[1:])
    if isinstance(rc, int) and rc:
        sys.exit(rc)


if __name__ == "__main__":
    main()
