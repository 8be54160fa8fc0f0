"""``python3 -m pcrf.plot …``: what ``pcrf plot …`` runs."""
import sys

from .cli import main

sys.exit(main(sys.argv[1:]))
