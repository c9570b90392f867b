#pragma once
#include <string>
#include <vector>

#include "machine/machine_profile.h"

namespace gearpatch {

/// The name of an element kind as a profile writes it ("function_generator").
std::string element_name(ElementKind kind);
/// Every element kind, in the order a patch sheet counts them.
const std::vector<ElementKind>& element_kinds();

/// The profiles shipped in machines/ (compiled into the binary): the-analog-thing, model-1 …
std::vector<std::string> machine_names();

/// Parses a machine profile (INI, the scene's syntax); `source` names it in
/// messages. Throws Error (kind input) naming file, line and key.
MachineProfile parse_machine_profile(const std::string& text, const std::string& source);

/// A shipped profile by name, else the file at that path (tried as given, then
/// beside `relative_to`, the file that names it). Throws Error for neither.
MachineProfile load_machine_profile(const std::string& name_or_file, const std::string& relative_to = "");

/// The profile's own text: the shipped one by name, else the file's.
std::string machine_profile_text(const std::string& name);

}  // namespace gearpatch
