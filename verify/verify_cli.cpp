// vismap verify SCENE MAP.json [--samples N] [--seed S] [--crease DEG] [--smooth] [--strict] [--format F]
// Checks a map in the spec's JSON format (written by any program) against its
// scene; exit 0 iff it holds. See kVerifyHelp.
#include "verify/verify_cli.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "engine/scene.h"
#include "verify/checker.h"

namespace vismap_check {

const char* const kVerifyHelp = R"(usage: vismap verify SCENE MAP.json [options]

Checks, independently and exactly, that MAP.json (in the vismap JSON format,
written by vismap or by any other program) is the visibility map of SCENE seen
through the view matrix written in the map: region labels at random rational
points against the brute-force nearest face (depth, then lowest index), the
exact total area of the regions, every segment visible along its interior and
of the right kind and faces, every visible edge and intersection line covered,
the topology, and the canonical format; where the map has "hidden" lines (made
with --hidden), each of them hidden and uncovered along its interior, of the
right kind and faces, every hidden stretch covered, none overlapping, each
maximal. Shares no code with the engines beyond the mesh readers and GMP.

Either SCENE or MAP.json (not both) may be "-" for standard input.

options:
  --samples N      random sample points for the region labels (default 2000)
  --seed S         seed of those points (default 1)
  --crease DEG     the crease angle the map was made with (default 30)
  --smooth         the map was made with --smooth (smooth edges are drawn)
  --strict         also check every stretch of every edge and intersection line,
                   hidden ones included: a segment exactly where the first
                   visible line (drawn or not) is drawn (slower)
  --format F       SCENE's format: off, obj, stl, ply or vmscene (default: by
                   extension; for standard input, by content)
  --max-memory SIZE  refuse a scene that would need more (e.g. 8G; default:
                   from physical memory)
  -h, --help       this text

output: one line per failure (first few of each kind, exact coordinates), then
"OK: ..." or "FAILED: ..." with the counts of what was checked.
exit status: 0 the map holds, 1 it does not (or SCENE or MAP.json cannot be
read), 2 bad usage
)";

namespace {

struct Usage : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::uint64_t parse_count(const std::string& opt, const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
  if (s.empty() || s[0] == '-' || s[0] == '+' || *end != '\0' || errno == ERANGE)
    throw Usage(opt + " expects a non-negative integer, got '" + s + "'");
  return v;
}

double parse_angle(const std::string& opt, const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v) || v < 0 || v > 180)
    throw Usage(opt + " expects an angle between 0 and 180, got '" + s + "'");
  return v;
}

// The whole of a file (or of standard input for "-"), refusing more than `max` bytes.
std::string slurp(const std::string& path, std::uint64_t max) {
  std::error_code ec;
  if (path != "-" && std::filesystem::is_directory(path, ec))
    throw vismap::InputError(path + ": is a directory, not a map file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(path == "-" ? stdin : std::fopen(path.c_str(), "rb"),
                                                   [](std::FILE* p) { return p == stdin ? 0 : std::fclose(p); });
  if (!f) throw vismap::InputError(path + ": cannot open file: " + std::strerror(errno));
  std::string data;
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) {
    data.append(buf, n);
    if (max != 0 && data.size() > max)
      throw vismap::InputError(path + ": the map is larger than the memory limit of " +
                               vismap::format_bytes(max) + " (--max-memory)");
  }
  if (std::ferror(f.get())) throw vismap::InputError(path + ": cannot read file: " + std::strerror(errno));
  return data;
}

}  // namespace

int verify_command(const std::vector<std::string>& args) {
  std::string scene_path, map_path, format;
  Options opt;
  vismap::ReadLimits limits;
  limits.max_memory = vismap::default_max_memory();
  bool have_scene = false, have_map = false;
  try {
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&]() -> const std::string& {
        if (i + 1 >= args.size()) throw Usage(a + " needs a value");
        return args[++i];
      };
      if (a == "-h" || a == "--help") {
        std::fputs(kVerifyHelp, stdout);
        return 0;
      } else if (a == "--samples") {
        opt.samples = parse_count(a, value());
      } else if (a == "--seed") {
        opt.seed = parse_count(a, value());
      } else if (a == "--crease") {
        opt.crease_deg = parse_angle(a, value());
      } else if (a == "--smooth") {
        opt.smooth = true;
      } else if (a == "--strict") {
        opt.strict = true;
      } else if (a == "--format") {
        format = value();
        if (format != "off" && format != "obj" && format != "stl" && format != "ply" && format != "vmscene")
          throw Usage("--format expects off, obj, stl, ply or vmscene, got '" + format + "'");
      } else if (a == "--max-memory") {
        const std::string& v = value();
        if (!vismap::parse_memory_size(v, limits.max_memory))
          throw Usage("--max-memory expects a size such as 512M or 8G, got '" + v + "'");
      } else if (a.size() > 1 && a[0] == '-') {
        throw Usage("unknown option " + a);
      } else if (!have_scene) {
        scene_path = a;
        have_scene = true;
      } else if (!have_map) {
        map_path = a;
        have_map = true;
      } else {
        throw Usage("more than a scene and a map given: '" + a + "'");
      }
    }
    if (!have_map) throw Usage(have_scene ? "no map file given" : "no scene file given");
    if (scene_path.empty() || map_path.empty()) throw Usage("empty file name");
    if (scene_path == "-" && map_path == "-") throw Usage("the scene and the map cannot both be standard input");
  } catch (const Usage& e) {
    std::fprintf(stderr, "vismap verify: %s\n(run 'vismap verify --help' for usage)\n", e.what());
    return 2;
  }

  vismap::Scene scene;
  std::string text;
  try {
    scene = vismap::read_scene(scene_path, limits, format);
    text = slurp(map_path, limits.max_memory);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "vismap verify: out of memory reading the input\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vismap verify: %s\n", e.what());
    return 1;
  }

  const Report rep = check_map(scene, text, opt);
  for (const std::string& f : rep.failures) std::printf("FAIL %s\n", f.c_str());
  std::printf("%s: %s against %s: %zu region samples, %zu segment points, %zu edge points checked\n",
              rep.ok ? "OK" : "FAILED", map_path.c_str(), scene_path.c_str(), rep.samples_checked,
              rep.segment_points_checked, rep.edge_points_checked);
  std::fflush(stdout);
  return rep.ok ? 0 : 1;
}

}  // namespace vismap_check
