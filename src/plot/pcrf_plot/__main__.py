"""``python3 -m pcrf_plot …``: what ``pcrf plot …`` runs."""
import sys

from pcrf_plot.cli import main

sys.exit(main(sys.argv[1:]))
