// The native answers the browser test compares the page with: reads a JSON array of
// {"demo": name, "params": {name: number}} from stdin and writes the array of answers
// (web/src/answers.hpp) as JSON, NaN as null (as the page writes them).
#include "answers.hpp"

#include <nlohmann/json.hpp>

#include <iostream>
#include <variant>

int main() {
  const nlohmann::json queries = nlohmann::json::parse(std::cin);
  nlohmann::json out = nlohmann::json::array();
  for (const auto& q : queries) {
    ellipsect::web::Params params;
    for (const auto& [name, value] : q.at("params").items()) params.emplace(name, value.get<double>());
    nlohmann::json answer = nlohmann::json::object();
    for (const auto& entry : ellipsect::web::answer(q.at("demo").get<std::string>(), params))
      std::visit([&](const auto& v) { answer[entry.first] = v; }, entry.second);
    out.push_back(answer);
  }
  std::cout << out.dump() << '\n';
}
