// detail::triangulate_filtered<2>, compiled with the project's flags.
#include "triangulate_filtered.hpp"

template dewall::Statistics dewall::detail::triangulate_filtered<2>(std::span<const kernel::Point_d<2>>,
                                                                     const Options&, std::vector<Simplex<2>>&,
                                                                     std::vector<std::uint8_t>*);
