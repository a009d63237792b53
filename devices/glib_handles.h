// Ownership of GLib objects and errors for the Aravis code
// (devices/aravis_frame_source.cc, devices/fake_genicam_camera.cc): a
// GObject held by a unique_ptr is unreferenced once, on every path, and a
// GError filled by a C call is freed with its holder.
//
//   GErrorHolder error;
//   GObjectPtr<ArvCamera> camera(arv_camera_new(name, error.out()));
//   if (!camera) return Status::IoError(name + ": " + error.message());
//
// Built only where Aravis is found (HEXCAL_HAVE_ARAVIS); not a public header.
#pragma once

#include <glib-object.h>

#include <memory>
#include <string>

namespace hexcal::workflow {

struct GObjectUnref {
  void operator()(void* object) const {
    if (object != nullptr) g_object_unref(object);
  }
};

// Owns one reference to a GObject (ArvCamera, ArvStream, ArvGvFakeCamera, ...).
template <typename T>
using GObjectPtr = std::unique_ptr<T, GObjectUnref>;

// The GError** of a C call. out() frees an earlier error first, so one holder
// can serve a sequence of calls; the destructor frees the last one.
class GErrorHolder {
 public:
  GErrorHolder() = default;
  GErrorHolder(const GErrorHolder&) = delete;
  GErrorHolder& operator=(const GErrorHolder&) = delete;
  ~GErrorHolder() { g_clear_error(&error_); }

  GError** out() {
    g_clear_error(&error_);
    return &error_;
  }
  bool failed() const { return error_ != nullptr; }
  const GError* get() const { return error_; }
  std::string message() const { return error_ != nullptr && error_->message != nullptr ? error_->message : ""; }

 private:
  GError* error_ = nullptr;
};

}  // namespace hexcal::workflow
