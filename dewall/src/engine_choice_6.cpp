// detail::run_chosen_engine<6>, compiled with the project's flags.
#include "engine_choice.hpp"

template dewall::Statistics dewall::detail::run_chosen_engine<6>(std::span<const kernel::Point_d<6>>, const Options&,
                                                                   Simplex_output<6>&);
