#include "engine/engine.hpp"
#include "engine/scene/scene_reader.hpp"
#include "library/api_errors.hpp"
#include "library/scene_impl.hpp"

namespace rockdd::api {

Error::Error(ErrorKind kind, const std::string& message)
    : std::runtime_error(message), kind_(kind) {}

// Out of line: the key function that gives Error one type_info, exported from librockdd.so,
// so that a consumer's catch (const rockdd::api::Error&) matches what the library throws.
Error::~Error() = default;

Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

Scene Scene::from_file(const std::string& path, const std::vector<std::string>& overrides) {
  return translate_errors(
      [&] { return Scene(std::make_unique<Impl>(Impl{rockdd::load_scene(path, overrides)})); });
}

Scene Scene::from_string(std::string_view text, const std::vector<std::string>& overrides,
                         const std::string& name) {
  return translate_errors([&] {
    rockdd::Scene scene = parse_scene(text, name, overrides);
    return Scene(std::make_unique<Impl>(Impl{std::move(scene)}));
  });
}

std::string Scene::name() const {
  return impl_->scene.name;
}

const char* version() {
  return rockdd::version();
}

}  // namespace rockdd::api
