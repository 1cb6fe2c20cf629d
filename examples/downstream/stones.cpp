// A wall of rounded stones, each hatched in its own direction: a libtex arrangement script
// written the thesis's way (partition, mappers, merge), built against an installed libtex.
//
//   stones OUT.svg [SEED]    (the same SEED gives the same bytes)
#include <cstdio>
#include <string>

#include <libtex/tex.hpp>

using namespace tex;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: stones OUT.svg [SEED]\n");
        return 2;
    }
    if (argc > 2) SetSeed(std::stoull(argv[2]));
    const double size = 1000;
    // About 40 cells over the window, each shrunk towards its centre: the stones.
    const Arrangement cells = UniformPartition(IrregularProperties(40 / (size * size)), KEEP_OUTSIDE);
    const Arrangement stones = MapToFaces([](const Face& f) { return Scale(Contour(f), 0.85); }, cells);
    // Hatching at 45 degrees, cut to the stones, and a smaller ring inside every other stone
    // (chosen by the stone's own random stream, so the same on any thread).
    const Arrangement hatching = Inside(StripesPartition(StripesProperties(pi / 4, 12)), stones, CROP);
    const Arrangement rings = MapToFaces(
        [](const Face& f) { return Random(f, 0, 1, 0) < 0.5 ? Scale(Contour(f), 0.5) : Curves(); }, stones);
    const Arrangement hatched = Union(Union(stones, rings), Outside(hatching, rings, CROP));
    const Curves drawn = ExportSVG(hatched, size, argv[1]);
    std::printf("%s: %zu curves\n", argv[1], drawn.size());
    return drawn.empty() ? 1 : 0;
}
