// detail::run_chosen_engine<2>, compiled with the project's flags.
#include "engine_choice.hpp"

template dewall::Statistics dewall::detail::run_chosen_engine<2>(std::span<const kernel::Point_d<2>>, const Options&,
                                                                   Simplex_output<2>&);
