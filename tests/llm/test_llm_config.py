"""Every preset loads through Hydra and makes valid settings; no key is ever in the config."""

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.llm import LLMConfigError, LLMSettings

PRESETS = ["openai", "openrouter", "ollama", "vllm", "llamacpp", "openai_compatible", "fake"]


@pytest.mark.parametrize("preset", PRESETS)
def test_presets(preset):
    s = LLMSettings.from_config(load_config([f"llm={preset}"]).llm)
    assert s.base_url.endswith("/v1") and s.model
    assert s.temperature == 0.3 and s.system_role == "system" and s.send_temperature
    assert s.max_retries >= 0 and s.timeout > 0
    assert s.api_key_env is None or s.api_key_env.isupper()


def test_default_is_local_openai_compatible():
    cfg = load_config()
    assert cfg.llm.provider == "openai_compatible" and cfg.llm.base_url == "http://127.0.0.1:8080/v1"
    assert cfg.llm_cache.mode == "off" and cfg.llm_ledger.content == "hash"


def test_keys_come_from_named_variables():
    assert load_config(["llm=openai"]).llm.api_key_env == "OPENAI_API_KEY"
    assert load_config(["llm=openrouter"]).llm.api_key_env == "OPENROUTER_API_KEY"


def test_bad_values_are_rejected():
    with pytest.raises(LLMConfigError, match="system_role"):
        LLMSettings.from_config({"system_role": "admin"})
    with pytest.raises(LLMConfigError, match="unknown llm settings"):
        LLMSettings.from_config({"modle": "x"})
