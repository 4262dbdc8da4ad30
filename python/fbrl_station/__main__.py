# SPDX-License-Identifier: MIT
"""python3 -m fbrl_station: the fbrl-station program."""
import sys

from .cli import main

sys.exit(main())
