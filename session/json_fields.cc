#include "session/json_fields.h"

#include <cmath>

namespace hexcal::workflow {
namespace {

const nlohmann::json& NullJson() {
  static const nlohmann::json null_value;
  return null_value;
}

}  // namespace

JsonFields::JsonFields(const nlohmann::json& node, std::string source)
    : JsonFields(&node, std::move(source), "", std::make_shared<Status>()) {
  if (!node.is_object()) Fail("", "expected a JSON object at the top level");
}

JsonFields::JsonFields(const nlohmann::json* node, std::string source, std::string path,
                       std::shared_ptr<Status> first_error)
    : node_(node), source_(std::move(source)), path_(std::move(path)), first_error_(std::move(first_error)) {}

std::string JsonFields::PathOf(const std::string& key) const {
  if (path_.empty()) return key;
  if (key.empty()) return path_;
  return path_ + "." + key;
}

void JsonFields::Fail(const std::string& key, const std::string& problem) {
  if (!first_error_->ok()) return;
  const std::string where = PathOf(key);
  *first_error_ = Status::BadInput(source_ + (where.empty() ? "" : ": key '" + where + "'") + ": " + problem);
}

bool JsonFields::Has(const std::string& key) const {
  if (!node_->is_object()) return false;
  auto it = node_->find(key);
  return it != node_->end() && !it->is_null();
}

const nlohmann::json* JsonFields::Field(const std::string& key, const char* expected) {
  if (!node_->is_object()) return nullptr;  // already reported by whoever made this reader
  auto it = node_->find(key);
  if (it == node_->end()) {
    Fail(key, std::string("missing (expected ") + expected + ")");
    return nullptr;
  }
  return &*it;
}

double JsonFields::Number(const std::string& key) {
  const nlohmann::json* field = Field(key, "a number");
  if (field == nullptr) return 0;
  if (!field->is_number() || !std::isfinite(field->get<double>())) {
    Fail(key, "expected a finite number");
    return 0;
  }
  return field->get<double>();
}

std::optional<double> JsonFields::OptionalNumber(const std::string& key) {
  if (!Has(key)) return std::nullopt;
  return Number(key);
}

int JsonFields::Int(const std::string& key) {
  const nlohmann::json* field = Field(key, "a whole number");
  if (field == nullptr) return 0;
  if (!field->is_number_integer()) {
    Fail(key, "expected a whole number");
    return 0;
  }
  return field->get<int>();
}

bool JsonFields::Bool(const std::string& key) {
  const nlohmann::json* field = Field(key, "true or false");
  if (field == nullptr) return false;
  if (!field->is_boolean()) {
    Fail(key, "expected true or false");
    return false;
  }
  return field->get<bool>();
}

std::string JsonFields::String(const std::string& key) {
  const nlohmann::json* field = Field(key, "a string");
  if (field == nullptr) return "";
  if (!field->is_string()) {
    Fail(key, "expected a string");
    return "";
  }
  return field->get<std::string>();
}

std::vector<double> JsonFields::Numbers(const std::string& key, size_t count) {
  std::vector<double> values;
  const nlohmann::json* field = Field(key, "a list of numbers");
  if (field == nullptr) return std::vector<double>(count, 0.0);
  if (!field->is_array() || field->size() != count) {
    Fail(key, "expected a list of " + std::to_string(count) + " numbers");
    return std::vector<double>(count, 0.0);
  }
  for (const nlohmann::json& value : *field) {
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      Fail(key, "expected finite numbers");
      return std::vector<double>(count, 0.0);
    }
    values.push_back(value.get<double>());
  }
  return values;
}

std::vector<int> JsonFields::Ints(const std::string& key) {
  std::vector<int> values;
  const nlohmann::json* field = Field(key, "a list of whole numbers");
  if (field == nullptr) return values;
  for (const nlohmann::json& value : field->is_array() ? *field : nlohmann::json::array({nullptr})) {
    if (!value.is_number_integer()) {
      Fail(key, "expected a list of whole numbers");
      return {};
    }
    values.push_back(value.get<int>());
  }
  return values;
}

std::vector<std::string> JsonFields::Strings(const std::string& key) {
  std::vector<std::string> values;
  const nlohmann::json* field = Field(key, "a list of strings");
  if (field == nullptr) return values;
  for (const nlohmann::json& value : field->is_array() ? *field : nlohmann::json::array({nullptr})) {
    if (!value.is_string()) {
      Fail(key, "expected a list of strings");
      return {};
    }
    values.push_back(value.get<std::string>());
  }
  return values;
}

JsonFields JsonFields::Object(const std::string& key) {
  const nlohmann::json* field = Field(key, "an object");
  if (field != nullptr && !field->is_object()) {
    Fail(key, "expected an object");
    field = nullptr;
  }
  return JsonFields(field != nullptr ? field : &NullJson(), source_, PathOf(key), first_error_);
}

std::vector<JsonFields> JsonFields::Array(const std::string& key) {
  std::vector<JsonFields> items;
  const nlohmann::json* field = Field(key, "a list");
  if (field == nullptr) return items;
  if (!field->is_array()) {
    Fail(key, "expected a list");
    return items;
  }
  for (size_t k = 0; k < field->size(); ++k) {
    const nlohmann::json& item = (*field)[k];
    const std::string path = PathOf(key) + "[" + std::to_string(k) + "]";
    if (!item.is_object()) {
      Fail(key + "[" + std::to_string(k) + "]", "expected an object");
      return {};
    }
    items.push_back(JsonFields(&item, source_, path, first_error_));
  }
  return items;
}

StatusOr<nlohmann::json> ParseJsonText(const std::string& text, const std::string& source) {
  nlohmann::json document = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) return Status::BadInput(source + ": not valid JSON");
  return document;
}

}  // namespace hexcal::workflow
