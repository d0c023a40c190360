// detail::triangulate_filtered<4>, compiled with the project's flags.
#include "triangulate_filtered.hpp"

template dewall::Statistics dewall::detail::triangulate_filtered<4>(std::span<const kernel::Point_d<4>>,
                                                                     const Options&, Simplex_output<4>&);
