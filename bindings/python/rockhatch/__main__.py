"""python3 -m rockhatch: the rockhatch command, with --script for Python style scripts,
`tiles` for a tiled run on Dask distributed (rockhatch.tiles) and `serve` for the web map
page (rockhatch.serve)."""
import sys

if len(sys.argv) > 1 and sys.argv[1] == "tiles":
    from .tiles import main as tiles_main

    sys.exit(tiles_main(sys.argv[2:]))

if len(sys.argv) > 1 and sys.argv[1] == "serve":
    from .serve import main as serve_main

    sys.exit(serve_main(sys.argv[2:]))

from .cli import main

sys.exit(main())
