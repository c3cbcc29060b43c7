//! Exports the `hertz-asperity` law through the Stiction law ABI (`stiction_law_descriptor`).
stiction_law_sdk::export_law!(stiction_law_hertz_asperity::HertzAsperity);
