// detail::triangulate_filtered<2>, compiled with the project's flags.
#include "triangulate_filtered.hpp"

template dewall::Statistics dewall::detail::triangulate_filtered<2>(std::span<const kernel::Point_d<2>>,
                                                                     const Options&, Simplex_output<2>&);
