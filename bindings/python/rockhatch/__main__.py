"""python3 -m rockhatch: the rockhatch command, with --script for Python style scripts."""
import sys

from .cli import main

sys.exit(main())
