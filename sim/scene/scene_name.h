#pragma once
// The scene's name is the folder its results go to (OUT/<name>/): letters, digits, _ - . only, so
// that it is one folder on every file system and needs no quoting in a shell or a Slurm script.
#include <string>

namespace spume {

bool is_usable_scene_name(const std::string& name);

// `text` made usable: each run of other characters becomes one '_', and '_', '-' and '.' at either
// end go ("my fluid " -> "my_fluid"). "" when nothing usable is left.
std::string usable_scene_name(const std::string& text);

}  // namespace spume
