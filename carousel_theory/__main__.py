import sys

from carousel_theory.cli import main

sys.exit(main())
