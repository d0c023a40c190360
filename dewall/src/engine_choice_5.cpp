// detail::run_chosen_engine<5>, compiled with the project's flags.
#include "engine_choice.hpp"

template dewall::Statistics dewall::detail::run_chosen_engine<5>(std::span<const kernel::Point_d<5>>, const Options&,
                                                                   Simplex_output<5>&);
