"""``python3 -m spt``."""

import sys

from .cli import main

sys.exit(main())
