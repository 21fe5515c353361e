// vismap's package from outside: CONSUMER SCENE OUT.json writes the map of SCENE
// seen along -1,-2,-3 (the command line's default camera, with --dir), and
// checks a scene built in code. Exit 0 when all is as expected.
#include <vismap/vismap.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: consumer SCENE OUT.json\n");
    return 2;
  }
  try {
    vismap::Camera camera;
    camera.dir = vismap::Vec3{-1, -2, -3};
    vismap::compute(vismap::read_scene(argv[1]), camera).write(argv[2]);
    // A triangle seen from above: one region, three border segments.
    vismap::Scene s;
    s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    s.faces = {{0, 1, 2}};
    camera.dir = vismap::Vec3{0, 0, -1};
    const vismap::Map m = vismap::compute(s, camera);
    if (m.regions().size() != 1 || m.segments().size() != 3 || m.exact(0).x != "0") {
      std::fprintf(stderr, "consumer: unexpected map of a triangle\n");
      return 1;
    }
    try {
      vismap::read_scene("missing.off");
      return 1;
    } catch (const vismap::InputError&) {   // the library's exception type reaches its user
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
