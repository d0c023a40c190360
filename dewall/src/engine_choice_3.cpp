// detail::run_chosen_engine<3>, compiled with the project's flags.
#include "engine_choice.hpp"

template dewall::Statistics dewall::detail::run_chosen_engine<3>(std::span<const kernel::Point_d<3>>, const Options&,
                                                                   Simplex_output<3>&);
