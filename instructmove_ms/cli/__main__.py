"""``python -m instructmove_ms.cli``: the ``instructmove`` command."""

import sys

from instructmove_ms.cli import main

sys.exit(main())
