"""`python3 -m lab`: set up on first use, then run the lab (`python3 -m lab test`: the tests)."""

import sys

from lab.bootstrap import main

sys.exit(main(sys.argv[1:]))
