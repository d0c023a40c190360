// detail::run_chosen_engine<4>, compiled with the project's flags.
#include "engine_choice.hpp"

template dewall::Statistics dewall::detail::run_chosen_engine<4>(std::span<const kernel::Point_d<4>>, const Options&,
                                                                   Simplex_output<4>&);
