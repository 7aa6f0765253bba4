#ifndef ROCKDD_EXPORT_H
#define ROCKDD_EXPORT_H
/* librockdd.so is built with hidden visibility: only what carries ROCKDD_API is exported. */
#if defined(__GNUC__)
#define ROCKDD_API __attribute__((visibility("default")))
#else
#define ROCKDD_API
#endif
#endif
