import sys

from pounding.cli.commands import main

sys.exit(main())
