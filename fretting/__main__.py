"""``python -m fretting``: the command line of `fretting.cli`."""

import sys

from fretting.cli import main

sys.exit(main())
