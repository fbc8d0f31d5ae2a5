"""``python -m rigor_gyro`` is the ``rigor-gyro`` command."""
import sys

from .cli import main

sys.exit(main())
