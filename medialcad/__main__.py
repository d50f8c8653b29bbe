import sys

from medialcad.cli import main

sys.exit(main())
