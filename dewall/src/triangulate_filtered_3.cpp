// detail::triangulate_filtered<3>, compiled with the project's flags.
#include "triangulate_filtered.hpp"

template dewall::Statistics dewall::detail::triangulate_filtered<3>(std::span<const kernel::Point_d<3>>,
                                                                     const Options&, Simplex_output<3>&);
