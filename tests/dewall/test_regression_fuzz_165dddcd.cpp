// Regression: fuzz finding 165dddcd (fuzz_triangulate, 2D). A subregion's face
// received an apex from the sibling region, so the face outlived the region's
// points and the next split failed (internal assertion). Found by the CI's short
// fuzz campaign; the input is also in fuzz/corpus/triangulate/.
#include <catch2/catch.hpp>

#include "dewall/dewall.hpp"
#include "support/cgal_reference.hpp"

TEST_CASE("regression fuzz 165dddcd: faces outliving their region's points", "[regression]") {
  using P = dewall::kernel::Point_d<2>;
  const std::vector<P> points{{{-0.99999999999999978, 11819748255234}},
                              {{1.2480187343462749e-243, -3.0000000000000013}},
                              {{11819748255232, -3.0887652673371129e+218}},
                              {{6.0000000000000018, -1.7650087241926359e+218}},
                              {{3.5300174483852719e+218, 1.4635779768233457e-314}},
                              {{-8, -8}}};
  for (int parallel : {0, 6}) {
    dewall::Options options;
    options.parallel_depth = parallel;
    options.engine = dewall::Engine::dewall;
    const auto t = dewall::triangulate<2>(points, options);
    CHECK(dewall::test::as_set<2>(t.simplices) == dewall::test::cgal_delaunay<2>(points));
    CHECK(t.simplices.size() == dewall::test::cgal_delaunay<2>(points).size());
  }
}
