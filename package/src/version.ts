// The package's version; scripts/build.mjs refuses to build when it differs from package.json's.
export const version = '0.1.0';
