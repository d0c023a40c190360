// detail::run_chosen_engine<4>, compiled with the project's flags.
#include "engine_choice.hpp"

DEWALL_INSTANTIATE_ENGINE_CHOICE(4)
