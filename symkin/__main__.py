"""``python -m symkin``: the command line."""

from symkin.cli import console_main

console_main()
