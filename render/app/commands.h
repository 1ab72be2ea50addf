#pragma once
#include <string>
#include <vector>

namespace spume {

// Each returns the process exit status; errors are thrown as spume::Error and reported by main.
int command_simulate(const std::vector<std::string>& args);
int command_render(const std::vector<std::string>& args);
int command_run(const std::vector<std::string>& args);
int command_lookdev(const std::vector<std::string>& args);
int command_farm(const std::vector<std::string>& args);
int command_info(const std::vector<std::string>& args);
int command_report(const std::vector<std::string>& args);
int command_compare(const std::vector<std::string>& args);

}  // namespace spume
