"""``python -m ddg_oracle``: the ``ddg-oracle`` command."""

import sys

from ddg_oracle.application.cli import main

sys.exit(main())
