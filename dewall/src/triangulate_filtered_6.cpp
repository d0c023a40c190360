// detail::triangulate_filtered<6>, compiled with the project's flags.
#include "triangulate_filtered.hpp"

template dewall::Statistics dewall::detail::triangulate_filtered<6>(std::span<const kernel::Point_d<6>>,
                                                                     const Options&, Simplex_output<6>&);
