// detail::triangulate_filtered<5>, compiled with the project's flags.
#include "triangulate_filtered.hpp"

template dewall::Statistics dewall::detail::triangulate_filtered<5>(std::span<const kernel::Point_d<5>>,
                                                                     const Options&, Simplex_output<5>&);
